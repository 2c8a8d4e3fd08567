#pragma once
// Waiting for a socket without paying to be woken. A process asleep in poll() is woken by the kernel when
// its peer's message arrives; with the peer on another CPU that wake-up (an inter-processor interrupt, the
// CPU leaving its idle state, on a virtual machine a trip through the hypervisor) costs 5-50 µs, several
// times a short request's own work. Client and server take turns, so the side that has just sent usually
// hears back within microseconds: each polls without sleeping for a short while first, yielding its CPU
// to anything else that is runnable there, and sleeps only when nothing came. The Python client does the
// same (spear/_rpc_client.py), with the same setting.

#include <poll.h>

#include <chrono>

namespace sp::rpc {

// How long this process polls before it sleeps: SPEAR_RPC_SPIN_US microseconds (default 100, at most
// 10000; 0 never polls without sleeping). None where the process may run on one CPU only, as there its
// polling would keep the CPU from the very peer it waits for. Throws InvalidArgument for a bad value.
std::chrono::microseconds spinFromEnvironment();

// poll(fds, count, timeoutMs), but polling without sleeping for up to `spin` first (within the timeout).
int pollSpinning(pollfd* fds, nfds_t count, int timeoutMs, std::chrono::microseconds spin);

} // namespace sp::rpc
