#include "core/reflect/property_path.h"

#include <cctype>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/reflect/registry.h"
#include "core/reflect/type_info.h"

namespace sp::reflect {
namespace {

// One segment: a name and the indices or keys after it ("Wheels[2]": "Wheels", {"2"}).
struct Segment {
    std::string name;
    std::vector<std::string> keys;
};

std::vector<Segment> parse(std::string_view path, std::string_view context) {
    std::vector<Segment> segments;
    std::size_t at = 0;
    auto bad = [&](const char* why) {
        SP_THROW(InvalidArgument, context, ": property path '", path, "' ", why, " at character ", at + 1);
    };
    while (true) {
        Segment segment;
        const std::size_t start = at;
        while (at < path.size() && (std::isalnum(static_cast<unsigned char>(path[at])) || path[at] == '_'))
            ++at;
        if (at == start)
            bad("expects a name");
        segment.name = std::string(path.substr(start, at - start));
        while (at < path.size() && path[at] == '[') {
            ++at;
            std::string key;
            if (at < path.size() && (path[at] == '\'' || path[at] == '"')) { // quoted: any characters
                const char quote = path[at++];
                const std::size_t close = path.find(quote, at);
                if (close == std::string_view::npos)
                    bad("has an unclosed quote");
                key = std::string(path.substr(at, close - at));
                at = close + 1;
            } else {
                const std::size_t close = path.find(']', at);
                if (close == at || at == path.size())
                    bad("expects an index or key in []");
                if (close == std::string_view::npos) {
                    at = path.size();
                    bad("expects ']'");
                }
                key = std::string(path.substr(at, close - at));
                at = close;
            }
            if (at >= path.size() || path[at] != ']')
                bad("expects ']'");
            ++at;
            segment.keys.push_back(std::move(key));
        }
        segments.push_back(std::move(segment));
        if (at == path.size())
            return segments;
        if (path[at] != '.')
            bad("expects '.' or '['");
        ++at;
    }
}

// Where a walk stands: on an object, or inside the value of `owner`'s property `property` (`whole`), at
// `current` (a part of `whole`) of declared type `type`. `shown` is the path so far, for messages.
struct Walk {
    ObjectBase* object = nullptr;
    ObjectBase* owner = nullptr;
    const PropertyInfo* property = nullptr;
    Value whole;
    Value* current = nullptr;
    TypeCode type;
    std::string shown;
};

// Steps from an object to its property `name`.
void intoProperty(Walk& walk, const std::string& name, std::string_view context) {
    const TypeInfo& type = walk.object->GetClass();
    const PropertyInfo* property = type.findProperty(name);
    SP_CHECK(property, NotFound, context, ": class '", type.name, "' has no property '", name, "'",
             walk.shown.empty() ? "" : " (at '" + walk.shown + "')");
    walk.owner = walk.object;
    walk.object = nullptr;
    walk.property = property;
    walk.whole = property->get(walk.owner);
    walk.current = &walk.whole;
    walk.type = property->type;
}

// Steps from a struct value to its field `name`.
void intoField(Walk& walk, const std::string& name, std::string_view context) {
    const TypeInfo* info =
        walk.type.kind == TypeCode::Kind::Struct ? Registry::get().findType(walk.type.name) : nullptr;
    SP_CHECK(info && walk.current->is<Value::Dict>(), NotFound, context, ": '", walk.shown, "' is ",
             walk.type.spelling(), ", which has no field '", name, "'");
    const PropertyInfo* field = info->findProperty(name);
    SP_CHECK(field, NotFound, context, ": struct '", info->name, "' has no field '", name, "' (at '",
             walk.shown, "')");
    walk.current = &walk.current->as<Value::Dict>()[name];
    walk.type = field->type;
}

// Steps into element `key` of a list or dict value; `adding` lets a dict gain the key.
void intoElement(Walk& walk, const std::string& key, bool adding, std::string_view context) {
    if (walk.type.kind == TypeCode::Kind::List && walk.current->is<Value::List>()) {
        Value::List& list = walk.current->as<Value::List>();
        std::size_t index = 0, used = 0;
        try {
            index = std::stoul(key, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        SP_CHECK(used == key.size() && key.find_first_not_of("0123456789") == std::string::npos,
                 InvalidArgument, context, ": '", walk.shown, "' is a list, indexed by a number, not '", key,
                 "'");
        SP_CHECK(index < list.size(), NotFound, context, ": '", walk.shown, "' has ", list.size(),
                 list.size() == 1 ? " item" : " items", ", no [", key, "]");
        walk.current = &list[index];
    } else if (walk.type.kind == TypeCode::Kind::Dict && walk.current->is<Value::Dict>()) {
        Value::Dict& dict = walk.current->as<Value::Dict>();
        if (!adding && dict.find(key) == dict.end()) {
            std::string keys;
            for (const auto& [name, item] : dict)
                keys += (keys.empty() ? "" : ", ") + ("'" + name + "'");
            SP_THROW(NotFound, context, ": '", walk.shown, "' has no key '", key, "' (",
                     keys.empty() ? std::string("it is empty") : "its keys: " + keys, ")");
        }
        walk.current = &dict[key]; // a write may add the key
    } else {
        SP_THROW(NotFound, context, ": '", walk.shown, "' is ", walk.type.spelling(),
                 ", not a list or dict, so it has no [", key, "]");
    }
    walk.type = walk.type.elementType();
}

// Steps from an object reference to the object it names.
void intoObject(Walk& walk, std::string_view context) {
    SP_CHECK(walk.current->is<ObjectHandle>() && !walk.current->as<ObjectHandle>().isNull(), NotFound,
             context, ": '", walk.shown, "' is None");
    walk.object = &ObjectTable::resolve(walk.current->as<ObjectHandle>(), context);
    walk.owner = nullptr;
    walk.property = nullptr;
    walk.current = nullptr;
}

// Walks `path` from `object` (in place: `walk.current` points into `walk.whole`).
void walkTo(Walk& walk, ObjectBase& object, std::string_view path, bool adding, std::string_view context) {
    const std::vector<Segment> segments = parse(path, context);
    walk.object = &object;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        const Segment& segment = segments[s];
        if (walk.current && walk.type.kind == TypeCode::Kind::Object)
            intoObject(walk, context);
        if (walk.object)
            intoProperty(walk, segment.name, context);
        else
            intoField(walk, segment.name, context);
        walk.shown += (s == 0 ? "" : ".") + segment.name;
        for (std::size_t k = 0; k < segment.keys.size(); ++k) {
            const bool last = s + 1 == segments.size() && k + 1 == segment.keys.size();
            intoElement(walk, segment.keys[k], adding && last, context);
            walk.shown += "[" + segment.keys[k] + "]";
        }
    }
}

} // namespace

PathValue getPath(ObjectBase& object, std::string_view path, std::string_view context) {
    Walk walk;
    walkTo(walk, object, path, false, context);
    return {std::move(*walk.current), std::move(walk.type)};
}

void setPath(ObjectBase& object, std::string_view path, Value value, std::string_view context) {
    Walk walk;
    walkTo(walk, object, path, true, context);
    SP_CHECK(walk.property->set, InvalidArgument, context, ": property '", walk.property->name,
             "' of class '", walk.owner->GetClass().name, "' is read-only");
    *walk.current = std::move(value);
    walk.property->set(walk.owner, walk.whole);
}

} // namespace sp::reflect
