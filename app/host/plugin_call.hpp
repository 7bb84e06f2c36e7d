// plugin_call.hpp - which plugin call a thread is in, so that a crash inside
// a plugin names the plugin and the call before the process dies:
//
//   arbor: plugin org.example.bad crashed (SIGSEGV) in simplifier.importance
//
// Every host call into plugin code runs inside a PluginCall (through
// PluginInstance::call, or directly for a library's entry functions).  The
// first one installs handlers for SIGSEGV, SIGBUS, SIGFPE, SIGILL and
// SIGABRT (SA_ONSTACK; each thread that calls plugins gets an alternate
// signal stack, so a stack overflow is reported too).  A handler only
// write()s the names it was given (async-signal-safe), puts back the action
// that was there before (the default, or a sanitizer's) and lets the signal
// take its course: the process still dies of that signal.  Nothing is
// recovered, only said.  A crash on a thread that is in no plugin call (a
// plugin's own worker thread) names the calls other threads are in.
//
// A call costs a few thread-local stores; nothing is formatted or allocated.
#pragma once

namespace arbor {

class PluginCall {
public:
    // `plugin`: the plugin's id (or a library's file name); `function`:
    // "interface.function" ("simplifier.importance").  Both must stay valid
    // during the call (string literals, a host-owned copy of the id).
    PluginCall(const char *plugin, const char *function) noexcept;
    ~PluginCall();
    PluginCall(const PluginCall &) = delete;
    PluginCall &operator=(const PluginCall &) = delete;

private:
    const char *outer_plugin_, *outer_function_; // the call this one is nested in
};

} // namespace arbor
