#pragma once
// SP_LOG("Input is [", x, "]") writes one line with a source location, as in the SPEAR paper's Fig. 8: to
// stderr ("[spear] file.cpp:12: message"), or to the sink a host installs. Lines from several threads never
// interleave.

#include <functional>
#include <string_view>

#include "core/base/error.h"

namespace sp::base {
void writeLogLine(std::string_view file, int line, std::string_view message);

// Where log lines go instead of stderr: the Python engine module routes them to Python's logging (logger
// "spear"). Called without any lock held, from whichever thread logs. nullptr restores stderr.
using LogSink = void (*)(std::string_view file, int line, std::string_view message);
void setLogSink(LogSink sink);

// Who else hears log lines besides the sink (the inspector's browsers): called after it, from the logging
// thread, under a lock of the listeners' own (a listener must not log, nor add or remove listeners). Returns
// the id removeLogListener takes.
using LogListener = std::function<void(std::string_view file, int line, std::string_view message)>;
int addLogListener(LogListener listener);
void removeLogListener(int id);
} // namespace sp::base

#define SP_LOG(...) ::sp::base::writeLogLine(__FILE__, __LINE__, ::sp::detail::concat(__VA_ARGS__))
