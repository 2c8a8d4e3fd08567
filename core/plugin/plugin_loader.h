#pragma once
// Plugins: shared libraries built by spear_add_plugin() (cmake/spearConfig.cmake) whose reflected classes
// join the engine's registry at run time. The in-process engine and spear-server load them through this
// one loader, so both transports see the same classes and the same errors.
//
// A plugin library lib<name>.so exports the generated entry points spear_register_<name>_types,
// spear_unregister_<name>_types and spear_register_<name>_types_api_hash (extern "C").

#include <string>
#include <vector>

#include "core/reflect/type_info.h"

namespace sp::plugin {

struct PluginInfo {
    std::string name;                 // the module name: lib<name>.so
    std::string path;                 // as given to load()
    std::string apiHash;              // of the plugin's generated API
    std::vector<std::string> classes; // the classes, structs and enums it registered, sorted
};

// Loads the plugin library at `pathOrName` and registers its types; a bare name ("my_plugin") is looked up
// in the directories of SPEAR_PLUGIN_PATH (lib<name>.so there or in <dir>/<name>/). Loading the same plugin
// again returns the loaded one. With `expectedApiHash`, a library built from other headers than the caller's
// stubs is refused. Throws NotFound for a missing file, InvalidArgument for a library that is not a plugin.
const PluginInfo& load(const std::string& pathOrName, const std::string& expectedApiHash = "");

// The file load() would open for `pathOrName`: a bare name looked up in SPEAR_PLUGIN_PATH (NotFound when it
// is not there), any other text as it is.
std::string resolve(const std::string& pathOrName);

// Whether `path` is the library that load() finds by its name in this process's SPEAR_PLUGIN_PATH (compared
// as canonical paths): a library the process's owner installed for it rather than any file a client names.
bool foundInSearchPath(const std::string& path);

// Unregisters the plugin's types, so that its classes can no longer be created or named. Its code stays
// mapped until the process ends (RTLD_NODELETE: glibc could not unmap a C++ library reliably anyway), so a
// process loads one build of a plugin; loading a rebuilt one means restarting the process. Throws
// InvalidState while objects of its classes are alive, NotFound when no plugin of that name is loaded.
void unload(const std::string& name);

// Called by unload() before it checks for live objects, with a test for "is this class the plugin's":
// the engine drops what it keeps of those classes itself (the worlds' default objects).
using ReleaseClasses = void (*)(bool (*isPluginClass)(const reflect::TypeInfo&));
void setReleaseHook(ReleaseClasses hook);

// The engine's API hash, set by the engine as it registers its types: load() refuses a plugin compiled
// against another engine API (its recorded hash differs, or it records none), naming both.
void setEngineApiHash(std::string hash);

} // namespace sp::plugin
