#pragma once
// The registry: every reflected type by name. Generated code calls add() from one registration function
// per generated module (no static initialisers, which a static library would silently drop), and the
// engine calls those functions once at start-up.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/reflect/type_info.h"

namespace sp::reflect {

class Registry {
  public:
    static Registry& get();

    // Adding the same TypeInfo twice is a no-op; two different types with one name is an error.
    void add(const TypeInfo& type);
    void add(const EnumInfo& info);
    // Removes a type that was added (a plugin being unloaded); removing an unknown type is a no-op.
    void remove(const TypeInfo& type);
    void remove(const EnumInfo& info);

    const TypeInfo* findType(std::string_view name) const;
    const EnumInfo* findEnum(std::string_view name) const;
    // Throws NotFound: "<context>: class 'AFoo' is not registered".
    // With `asset`, a class that is not registered yet is loaded from that file by the class loader
    // (blueprints: the engine installs sp::scene::loadBlueprint).
    const TypeInfo& getClass(std::string_view name, std::string_view context,
                             const std::string& asset = "") const;

    // Throw NotFound: "<context>: struct 'FFoo' is not registered" (and likewise for an enum).
    const TypeInfo& getStruct(std::string_view name, std::string_view context) const;
    const EnumInfo& getEnum(std::string_view name, std::string_view context) const;

    using ClassLoader = const TypeInfo& (*)(const std::string& asset, std::string_view context);
    void setClassLoader(ClassLoader loader) { loader_ = loader; }
    // Loads the class asset at `asset` with the class loader (UWorld.load_class); InvalidState naming
    // `context` when none is installed (a registry used without an engine).
    const TypeInfo& loadClass(const std::string& asset, std::string_view context) const;

    std::vector<const TypeInfo*> types() const; // sorted by name
    std::vector<const EnumInfo*> enums() const;
    std::vector<const TypeInfo*> derivedClasses(const TypeInfo& base) const; // includes base, sorted

  private:
    std::map<std::string, const TypeInfo*, std::less<>> types_;
    std::map<std::string, const EnumInfo*, std::less<>> enums_;
    ClassLoader loader_ = nullptr;
};

} // namespace sp::reflect
