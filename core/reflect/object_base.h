#pragma once
// ObjectBase: what every reflected class derives from (through UObject). It gives each object a
// generation-checked handle in the process-wide object table, so that Python and RPC clients hold
// handles, never pointers, and a destroyed object is reported instead of crashing the engine.

#include <string>
#include <string_view>
#include <vector>

#include "core/reflect/value.h"

namespace sp::reflect {

class TypeInfo;

class ObjectBase {
  public:
    ObjectBase();
    virtual ~ObjectBase();
    ObjectBase(const ObjectBase&) = delete;
    ObjectBase& operator=(const ObjectBase&) = delete;

    ObjectHandle GetHandle() const { return handle_; }
    // Defined by generated code for every reflected class (declared by SP_GENERATED_BODY()).
    virtual const TypeInfo& GetClass() const = 0;
    // The class this object reports: the data-defined class (blueprint) it was created as, or GetClass().
    // Class queries (IsA, class names, scene files) use this; code that needs the generated class (Python
    // wrappers, RPC proxies) uses GetClass().
    const TypeInfo& GetObjectClass() const { return dataDefinedClass_ ? *dataDefinedClass_ : GetClass(); }
    // Makes this object report `type`, a data-defined class whose native class is GetClass(); set once,
    // right after construction.
    void SetDataDefinedClass(const TypeInfo& type);
    // Used in messages about this object, and remembered after it is destroyed.
    virtual std::string GetDebugName() const;
    // Called after a property was written through the registry or from Python.
    virtual void PostPropertyChanged(std::string_view /*propertyName*/) {}

    bool IsA(const TypeInfo& type) const;

  private:
    ObjectHandle handle_;
    const TypeInfo* dataDefinedClass_ = nullptr;
};

// The process-wide table of live objects. Slots are reused with a new generation, so an old handle
// never resolves to a new object.
class ObjectTable {
  public:
    // nullptr when the handle is null or stale.
    static ObjectBase* find(ObjectHandle handle);
    // Throws StaleObject ("<context>: AActor 'Cube' (object 5:2) was destroyed") or InvalidArgument for null.
    static ObjectBase& resolve(ObjectHandle handle, std::string_view context);
    static size_t liveCount();
    // Every live object, in handle order.
    static std::vector<ObjectBase*> liveObjects();
    // Records the object's debug name for messages about its handle after it is gone. Whoever destroys
    // objects calls this first, while the object is whole (a destructor can no longer ask it).
    static void rememberName(const ObjectBase& object);

  private:
    friend class ObjectBase;
    static ObjectHandle insert(ObjectBase* object);
    static void erase(ObjectHandle handle);
};

} // namespace sp::reflect
