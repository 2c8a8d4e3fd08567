#pragma once
// ValueCodec<T>: checked conversion between Values and the C++ types that may cross the boundary.
// Generated invokers call encode()/decode(); every failure is an InvalidArgument whose message starts
// with the caller's context ("AActor.SetActorLocation(): parameter 'NewLocation'") and says what was
// expected and what arrived.

#include <charconv>
#include <concepts>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "core/base/error.h"
#include "core/reflect/class_ref.h"
#include "core/reflect/object_base.h"
#include "core/reflect/registry.h"
#include "core/reflect/sp_array.h"
#include "core/reflect/type_info.h"
#include "core/reflect/value.h"

namespace sp::reflect {

template <typename T> struct ValueCodec;

template <typename T> Value encode(const T& value) {
    return ValueCodec<T>::encode(value);
}
template <typename T> T decode(const Value& value, std::string_view context) {
    return ValueCodec<T>::decode(value, context);
}

[[noreturn]] inline void throwTypeMismatch(std::string_view context, std::string_view expected,
                                           const Value& got) {
    SP_THROW(InvalidArgument, context, " must be ", expected, ", got ", got.kindName(), " ", got.repr());
}

template <typename T>
concept ReflectedStruct = requires {
    T::StaticClass();
}
&&!std::derived_from<T, ObjectBase>;

template <> struct ValueCodec<bool> {
    static Value encode(bool v) { return Value(v); }
    static bool decode(const Value& v, std::string_view context) {
        if (const bool* b = v.tryAs<bool>())
            return *b;
        throwTypeMismatch(context, "a bool", v);
    }
};

template <std::integral T>
requires(!std::same_as<T, bool>) struct ValueCodec<T> {
    static Value encode(T v) { return Value(int64_t(v)); }
    static T decode(const Value& v, std::string_view context) {
        const int64_t* i = v.tryAs<int64_t>();
        if (const EnumValue* entry = v.tryAs<EnumValue>()) // an IntEnum is an int (as Python and mypy say)
            i = &entry->value;
        if (!i)
            throwTypeMismatch(context, "an int", v);
        if constexpr (std::is_unsigned_v<T>) {
            SP_CHECK(*i >= 0 && uint64_t(*i) <= std::numeric_limits<T>::max(), InvalidArgument, context,
                     " is out of range: ", *i);
        } else {
            SP_CHECK(*i >= std::numeric_limits<T>::min() && *i <= std::numeric_limits<T>::max(),
                     InvalidArgument, context, " is out of range: ", *i);
        }
        return T(*i);
    }
};

template <std::floating_point T> struct ValueCodec<T> {
    static Value encode(T v) { return Value(double(v)); }
    static T decode(const Value& v, std::string_view context) {
        if (const double* d = v.tryAs<double>())
            return T(*d);
        if (const int64_t* i = v.tryAs<int64_t>()) // Python passes 1 for 1.0
            return T(*i);
        if (const EnumValue* entry = v.tryAs<EnumValue>()) // and an IntEnum is an int
            return T(entry->value);
        throwTypeMismatch(context, "a float", v);
    }
};

template <> struct ValueCodec<std::string> {
    static Value encode(const std::string& v) { return Value(v); }
    static std::string decode(const Value& v, std::string_view context) {
        if (const std::string* s = v.tryAs<std::string>())
            return *s;
        throwTypeMismatch(context, "a str", v);
    }
};

// While one exists on this thread, an enum also takes a bare int: for values read from JSON (an SpFunc's
// unreal_objs), which has no enums; Python's json writes an IntEnum as its int.
class AcceptIntsForEnums {
  public:
    AcceptIntsForEnums() { ++depth(); }
    ~AcceptIntsForEnums() { --depth(); }
    AcceptIntsForEnums(const AcceptIntsForEnums&) = delete;
    AcceptIntsForEnums& operator=(const AcceptIntsForEnums&) = delete;
    static bool active() { return depth() > 0; }

  private:
    static int& depth() {
        thread_local int value = 0;
        return value;
    }
};

template <typename E>
requires std::is_enum_v<E>
struct ValueCodec<E> {
    static Value encode(E v) { return Value(EnumValue{StaticEnum<E>().name, int64_t(v)}); }
    // Only a value of this enum: a bare int (or another enum's entry) is refused, as pybind11 refuses it.
    static E decode(const Value& v, std::string_view context) {
        const EnumInfo& info = StaticEnum<E>();
        const EnumValue* entry = v.tryAs<EnumValue>();
        const int64_t* number = entry && entry->type == info.name ? &entry->value : nullptr;
        if (!entry && AcceptIntsForEnums::active())
            number = v.tryAs<int64_t>();
        if (!number)
            throwTypeMismatch(context, info.name, v);
        SP_CHECK(info.contains(*number), InvalidArgument, context, ": ", *number, " is not a value of ",
                 info.name);
        return E(*number);
    }
};

// A complete TypedDict's array field must hold an array when the struct leaves C++: its Python type
// promises the key. Names the struct and the field (after `context`, the function, when known), since
// the C++ code that forgot the field is the bug.
inline void checkFieldSet(const ArrayValue& array, std::string_view structName, std::string_view field,
                          std::string_view context = {}) {
    SP_CHECK(array.data, InvalidState, context, context.empty() ? "" : ": ", structName, ".", field,
             " was not set: every field of a TypedDict result must be set (SPSTRUCT(TypedDict, Partial) "
             "lets a field be left out)");
}

// Called by generated code on a function's struct result, so that a forgotten field of a complete
// TypedDict is reported with the function's name ("AMeasurer.Measure(): FMeasurement.Counts was not
// set ..."); the struct's encoders check again for structs that leave by other paths.
template <ReflectedStruct T> void checkResultFields(const T& result, std::string_view context) {
    const TypeInfo& type = T::StaticClass();
    if (!type.isCompleteDict)
        return;
    for (const PropertyInfo* property : type.allProperties())
        if (const Value field = property->get(&result); const ArrayValue* array = field.tryAs<ArrayValue>())
            checkFieldSet(*array, type.name, property->name, context);
}

template <ReflectedStruct T> struct ValueCodec<T> {
    static Value encode(const T& v) {
        const TypeInfo& type = T::StaticClass();
        Value::Dict fields;
        for (const PropertyInfo* property : type.allProperties()) {
            Value field = property->get(&v);
            // An array field that holds nothing is left out (a partial TypedDict has only what was produced).
            if (const ArrayValue* array = field.tryAs<ArrayValue>(); array && !array->data) {
                if (type.isCompleteDict)
                    checkFieldSet(*array, type.name, property->name);
                continue;
            }
            fields.emplace(property->name, std::move(field));
        }
        return Value(std::move(fields));
    }
    static T decode(const Value& v, std::string_view context) {
        const TypeInfo& type = T::StaticClass();
        const Value::Dict* fields = v.tryAs<Value::Dict>();
        if (!fields)
            throwTypeMismatch(context, type.name, v);
        T result{};
        for (const auto& [name, field] : *fields) {
            const PropertyInfo* property = type.findProperty(name);
            SP_CHECK(property, InvalidArgument, context, ": ", type.name, " has no field '", name, "'");
            try {
                property->set(&result, field);
            } catch (const InvalidArgument& e) { // the field's own message, after what was being decoded
                SP_THROW(InvalidArgument, context, ": ", e.what());
            }
        }
        return result;
    }
};

template <typename T>
requires std::derived_from<T, ObjectBase>
struct ValueCodec<T*> {
    static Value encode(const T* v) { return v ? Value(v->GetHandle()) : Value(); }
    static T* decode(const Value& v, std::string_view context) {
        if (v.isNone())
            return nullptr;
        const ObjectHandle* handle = v.tryAs<ObjectHandle>();
        if (!handle)
            throwTypeMismatch(context, T::StaticClass().name, v);
        ObjectBase& object = ObjectTable::resolve(*handle, context);
        SP_CHECK(object.IsA(T::StaticClass()), InvalidArgument, context, " must be ", T::StaticClass().name,
                 ", got ", object.GetDebugName());
        return static_cast<T*>(&object);
    }
};

template <> struct ValueCodec<const UClass*> {
    static Value encode(const UClass* v) { return v ? Value(ClassName{v->name}) : Value(); }
    static const UClass* decode(const Value& v, std::string_view context) {
        if (v.isNone())
            return nullptr;
        if (const ClassName* c = v.tryAs<ClassName>())
            return &Registry::get().getClass(c->name, context, c->asset);
        if (const std::string* s = v.tryAs<std::string>())
            return &Registry::get().getClass(*s, context);
        throwTypeMismatch(context, "a class", v);
    }
};

template <typename T> struct ValueCodec<TSubclassOf<T>> {
    static Value encode(const TSubclassOf<T>& v) { return ValueCodec<const UClass*>::encode(v.Get()); }
    static TSubclassOf<T> decode(const Value& v, std::string_view context) {
        const UClass* type = ValueCodec<const UClass*>::decode(v, context);
        SP_CHECK(!type || type->isChildOf(T::StaticClass()), InvalidArgument, context, ": class '",
                 type->name, "' does not derive from ", T::StaticClass().name);
        return TSubclassOf<T>(type);
    }
};

template <typename T> struct ValueCodec<std::vector<T>> {
    static Value encode(const std::vector<T>& v) {
        Value::List items;
        items.reserve(v.size());
        for (const auto& item : v)
            items.push_back(ValueCodec<T>::encode(item));
        return Value(std::move(items));
    }
    static std::vector<T> decode(const Value& v, std::string_view context) {
        const Value::List* items = v.tryAs<Value::List>();
        if (!items)
            throwTypeMismatch(context, "a list", v);
        std::vector<T> result;
        result.reserve(items->size());
        // Each item's context ("Components[12]") in one reused string: formatted through a string stream per
        // item, the names cost a list of 64 objects 20-30 us of a call whose work takes 50.
        std::string itemContext(context);
        itemContext += '[';
        const size_t prefix = itemContext.size();
        for (size_t i = 0; i < items->size(); ++i) {
            char digits[24];
            const char* end = std::to_chars(digits, digits + sizeof(digits), i).ptr;
            itemContext.resize(prefix);
            itemContext.append(digits, std::size_t(end - digits)).push_back(']');
            result.push_back(ValueCodec<T>::decode((*items)[i], itemContext));
        }
        return result;
    }
};

template <typename T> struct ValueCodec<std::map<std::string, T>> {
    static Value encode(const std::map<std::string, T>& v) {
        Value::Dict items;
        for (const auto& [key, item] : v)
            items.emplace(key, ValueCodec<T>::encode(item));
        return Value(std::move(items));
    }
    static std::map<std::string, T> decode(const Value& v, std::string_view context) {
        const Value::Dict* items = v.tryAs<Value::Dict>();
        if (!items)
            throwTypeMismatch(context, "a dict", v);
        std::map<std::string, T> result;
        for (const auto& [key, item] : *items)
            result.emplace(key, ValueCodec<T>::decode(item, detail::concat(context, "['", key, "']")));
        return result;
    }
};

template <typename T> struct ValueCodec<SpArray<T>> {
    static Value encode(const SpArray<T>& v) { return Value(v.value()); }
    static SpArray<T> decode(const Value& v, std::string_view context) {
        const ArrayValue* array = v.tryAs<ArrayValue>();
        if (!array)
            throwTypeMismatch(context, detail::concat("an ndarray of ", dtypeName(DTypeOf<T>::value)), v);
        SpArray<T> result;
        result.assign(*array, context);
        return result;
    }
};

// Looks up a call argument by name; absent arguments are an error unless the caller has a default.
inline const Value* findArgument(const CallArgs& args, const char* name) {
    auto it = args.find(name);
    return it == args.end() ? nullptr : &it->second;
}

} // namespace sp::reflect
