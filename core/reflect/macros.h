#pragma once
// Reflection macros. A class, struct, enum, property or function is reflected when it is marked with
// one of these; the generator (codegen/) reads the marks through libclang and emits the registry, the
// pybind11 module, the .pyi stubs and the RPC proxies from one IR.
//
// When the generator parses a header it defines SPEAR_GENERATOR, and the marks become clang
// `annotate` attributes, which libclang reports as ANNOTATE_ATTR cursors carrying the macro arguments.
// A mark on a class or struct cannot be an attribute of that class (UE places it before the `class`
// keyword, where an attribute would not attach), so it becomes an annotated marker declaration that
// the generator pairs with the next class definition in the same file.
//
// In a normal build the marks expand to nothing, and SP_GENERATED_BODY() declares the accessors whose
// definitions the generator writes.
//
// The UE spellings (UCLASS, USTRUCT, UENUM, UPROPERTY, UFUNCTION, GENERATED_BODY) are aliases, so that
// UE-style code compiles with only its include line changed.

namespace sp::reflect {
class TypeInfo;
} // namespace sp::reflect

#define SP_REFLECT_CONCAT_INNER(a, b) a##b
#define SP_REFLECT_CONCAT(a, b) SP_REFLECT_CONCAT_INNER(a, b)

// Declarations every reflected class or struct gets; the definitions are generated.
#define SP_REFLECT_BODY_DECLARATIONS                                                                         \
  public:                                                                                                    \
    static const ::sp::reflect::TypeInfo& StaticClass();                                                     \
    const ::sp::reflect::TypeInfo& GetClass() const;

#ifdef SPEAR_GENERATOR

#define SP_REFLECT_ANNOTATE(kind, ...) __attribute__((annotate("sp:" kind ":" #__VA_ARGS__)))
#define SP_REFLECT_TYPE_MARKER(kind, ...)                                                                    \
    struct SP_REFLECT_ANNOTATE(kind, __VA_ARGS__) SP_REFLECT_CONCAT(SpReflectMarker_, __COUNTER__);

#define SPCLASS(...) SP_REFLECT_TYPE_MARKER("class", __VA_ARGS__)
#define SPSTRUCT(...) SP_REFLECT_TYPE_MARKER("struct", __VA_ARGS__)
#define SPENUM(...) SP_REFLECT_TYPE_MARKER("enum", __VA_ARGS__)
#define SPPROPERTY(...) SP_REFLECT_ANNOTATE("property", __VA_ARGS__)
#define SPFUNCTION(...) SP_REFLECT_ANNOTATE("function", __VA_ARGS__)
#define SP_GENERATED_BODY()                                                                                  \
  public:                                                                                                    \
    SP_REFLECT_ANNOTATE("generated_body") static void SpReflectGeneratedBody_();                             \
    SP_REFLECT_BODY_DECLARATIONS

#else

#define SPCLASS(...)
#define SPSTRUCT(...)
#define SPENUM(...)
#define SPPROPERTY(...)
#define SPFUNCTION(...)
#define SP_GENERATED_BODY() SP_REFLECT_BODY_DECLARATIONS

#endif

#define UCLASS(...) SPCLASS(__VA_ARGS__)
#define USTRUCT(...) SPSTRUCT(__VA_ARGS__)
#define UENUM(...) SPENUM(__VA_ARGS__)
#define UPROPERTY(...) SPPROPERTY(__VA_ARGS__)
#define UFUNCTION(...) SPFUNCTION(__VA_ARGS__)
#define GENERATED_BODY() SP_GENERATED_BODY()
