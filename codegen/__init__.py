"""spear's binding generator: reflected C++ headers -> one IR -> registry, pybind11, stubs, RPC proxies."""
