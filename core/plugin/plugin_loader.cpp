#include "core/plugin/plugin_loader.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "core/base/error.h"
#include "core/base/regular_file.h"
#include "core/reflect/object_base.h"
#include "core/reflect/registry.h"

namespace sp::plugin {

namespace {
struct Loaded {
    PluginInfo info;
    void* library = nullptr;
    void (*unregister)() = nullptr;
};

std::map<std::string, Loaded>& plugins() {
    static std::map<std::string, Loaded> instance;
    return instance;
}

// Names of every plugin this process has loaded, and the API of the build it loaded.
std::map<std::string, std::string>& everLoaded() {
    static std::map<std::string, std::string> instance;
    return instance;
}

ReleaseClasses releaseHook = nullptr;
// The classes of the plugin being unloaded, for the release hook's test (unload is not reentrant).
std::vector<const reflect::TypeInfo*> unloading;

bool isUnloadingClass(const reflect::TypeInfo& type) {
    return std::any_of(unloading.begin(), unloading.end(),
                       [&](const auto* own) { return type.isChildOf(*own); });
}

// A plugin named without a path ("my_plugin"): lib<name>.so in a directory of SPEAR_PLUGIN_PATH, or in the
// package directory <dir>/<name>/ that spear_add_plugin() makes.
std::string findByName(const std::string& name) {
    const char* searchPath = std::getenv("SPEAR_PLUGIN_PATH");
    std::string dirs = searchPath ? searchPath : "";
    for (size_t start = 0; start <= dirs.size();) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path dir = dirs.substr(start, end - start);
        start = end + 1;
        if (dir.empty())
            continue;
        for (const auto& candidate : {dir / ("lib" + name + ".so"), dir / name / ("lib" + name + ".so")})
            if (std::filesystem::is_regular_file(candidate))
                return candidate.string();
    }
    SP_THROW(NotFound, "load_plugin(): no plugin named '", name, "' in SPEAR_PLUGIN_PATH (",
             dirs.empty() ? std::string("unset") : "'" + dirs + "'", "); give the path of its lib", name,
             ".so, or add the directory that holds it");
}

bool isBareName(const std::string& text) {
    return !text.empty() && text.find('/') == std::string::npos && !text.ends_with(".so");
}

// lib<name>.so -> name
std::string moduleName(const std::string& path) {
    std::string file = std::filesystem::path(path).filename().string();
    SP_CHECK(file.starts_with("lib") && file.ends_with(".so") && file.size() > 6, InvalidArgument,
             "load_plugin(): '", path, "' is not a plugin library (expected lib<name>.so)");
    return file.substr(3, file.size() - 6);
}

std::set<std::string> registeredNames() {
    std::set<std::string> names;
    for (const reflect::TypeInfo* type : reflect::Registry::get().types())
        names.insert(type->name);
    for (const reflect::EnumInfo* info : reflect::Registry::get().enums())
        names.insert(info->name);
    return names;
}

std::string& engineApiHash() {
    static std::string hash;
    return hash;
}

template <typename Fn> Fn symbol(void* library, const std::string& name, const std::string& path) {
    void* address = dlsym(library, name.c_str());
    if (!address) {
        dlclose(library);
        SP_THROW(InvalidArgument, "load_plugin(): '", path, "' is not a spear plugin (it has no ", name, ")");
    }
    return reinterpret_cast<Fn>(address);
}
} // namespace

std::string resolve(const std::string& pathOrName) {
    return isBareName(pathOrName) ? findByName(pathOrName) : pathOrName;
}

bool foundInSearchPath(const std::string& path) {
    const std::string file = std::filesystem::path(path).filename().string();
    if (!file.starts_with("lib") || !file.ends_with(".so") || file.size() <= 6)
        return false;
    std::string found;
    try {
        found = findByName(file.substr(3, file.size() - 6));
    } catch (const NotFound&) {
        return false;
    }
    std::error_code error, foundError;
    const auto canonical = std::filesystem::weakly_canonical(path, error);
    const auto canonicalFound = std::filesystem::weakly_canonical(found, foundError);
    return !error && !foundError && canonical == canonicalFound;
}

const PluginInfo& load(const std::string& pathOrName, const std::string& expectedApiHash) {
    const std::string path = resolve(pathOrName);
    const std::string name = moduleName(path);
    if (auto it = plugins().find(name); it != plugins().end()) {
        SP_CHECK(expectedApiHash.empty() || it->second.info.apiHash == expectedApiHash, InvalidState,
                 "load_plugin(): plugin '", name, "' is loaded with another API (", it->second.info.apiHash,
                 ")");
        return it->second.info;
    }
    SP_CHECK(std::filesystem::exists(path), NotFound, "load_plugin(): '", path, "' does not exist");
    // dlopen() of a FIFO would block for good. An engine file: which libraries may load is the plugin
    // policy's decision (the server's --plugin, its plugin path), not the user file roots'.
    checkRegularFile(path, "load_plugin()", "plugin library", kMaxUserFileBytes, FileScope::Engine);
    // RTLD_LOCAL: two plugins never resolve each other's symbols; RTLD_NOW: a missing symbol fails here;
    // RTLD_NODELETE: see unload(). An absolute path, so that dlopen() opens the file that was checked
    // rather than searching the library path for its name.
    const std::string absolute = std::filesystem::absolute(path).string();
    void* library = dlopen(absolute.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    SP_CHECK(library, InvalidArgument, "load_plugin(): cannot load '", path, "': ", dlerror());
    const std::string prefix = "spear_register_" + name + "_types";
    auto registerTypes = symbol<void (*)()>(library, prefix, path);
    auto apiHash = symbol<const char* (*)()>(library, prefix + "_api_hash", path);
    auto unregisterTypes = symbol<void (*)()>(library, "spear_unregister_" + name + "_types", path);
    if (!expectedApiHash.empty() && expectedApiHash != apiHash()) {
        const std::string actual = apiHash();
        dlclose(library);
        if (everLoaded().count(name))
            SP_THROW(InvalidState, "load_plugin(): this process already ran another build of plugin '", name,
                     "' (API ", actual,
                     "), whose code stays loaded; restart the process (the spear-server, or "
                     "Python for an in-process engine) to load the rebuilt one (API ",
                     expectedApiHash, ")");
        SP_THROW(InvalidState, "load_plugin(): '", path, "' was built from other headers (API ", actual,
                 ") than the Python package that loads it (API ", expectedApiHash, "); rebuild the plugin");
    }
    if (!engineApiHash().empty()) {
        const auto builtAgainst =
            reinterpret_cast<const char* (*)()>(dlsym(library, (prefix + "_engine_api_hash").c_str()));
        const std::string recorded = builtAgainst ? builtAgainst() : "none recorded";
        if (recorded != engineApiHash()) {
            dlclose(library);
            SP_THROW(InvalidState, "load_plugin(): '", path, "' was built against another engine API (",
                     recorded, ") than this engine's (", engineApiHash(),
                     "); rebuild the plugin against this spear");
        }
    }
    const std::set<std::string> before = registeredNames();
    try {
        registerTypes();
    } catch (...) {
        unregisterTypes();
        dlclose(library);
        throw;
    }
    everLoaded()[name] = apiHash();
    Loaded loaded{{name, path, apiHash(), {}}, library, unregisterTypes};
    for (const std::string& type : registeredNames())
        if (!before.count(type))
            loaded.info.classes.push_back(type);
    return plugins().emplace(name, std::move(loaded)).first->second.info;
}

void unload(const std::string& name) {
    auto it = plugins().find(name);
    SP_CHECK(it != plugins().end(), NotFound, "unload_plugin(): no plugin named '", name, "' is loaded");
    unloading.clear();
    for (const std::string& type : it->second.info.classes)
        if (const reflect::TypeInfo* info = reflect::Registry::get().findType(type))
            unloading.push_back(info);
    if (releaseHook)
        releaseHook(&isUnloadingClass);
    std::string alive;
    size_t count = 0;
    for (const reflect::ObjectBase* object : reflect::ObjectTable::liveObjects()) {
        if (!isUnloadingClass(object->GetClass()))
            continue;
        if (++count <= 3)
            alive += (alive.empty() ? "" : ", ") + object->GetDebugName();
    }
    SP_CHECK(count == 0, InvalidState, "unload_plugin('", name, "'): ", count,
             " object(s) of its classes are alive (", alive, count > 3 ? ", ..." : "",
             "); destroy them first");
    // Data-defined classes (blueprints) made from the plugin's classes go with them.
    for (const reflect::TypeInfo* type : reflect::Registry::get().types())
        if (type->isDataDefined() && isUnloadingClass(*type))
            reflect::Registry::get().remove(*type);
    it->second.unregister();
    dlclose(it->second.library); // with RTLD_NODELETE, the code stays mapped
    plugins().erase(it);
    unloading.clear();
}

void setReleaseHook(ReleaseClasses hook) {
    releaseHook = hook;
}

void setEngineApiHash(std::string hash) {
    engineApiHash() = std::move(hash);
}

} // namespace sp::plugin
