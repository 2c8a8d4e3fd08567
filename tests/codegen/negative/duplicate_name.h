// expect: tests/codegen/negative/duplicate_name.h:14: error: 'FSpan' is already the name of a reflected type in tests/codegen/negative/duplicate_name.h; reflected names are global (rename one)
#include "core/reflect/macros.h"

namespace first {
SPSTRUCT()
struct FSpan {
    SP_GENERATED_BODY()
    SPPROPERTY() double Length = 0.0;
};
} // namespace first

namespace second {
SPSTRUCT()
struct FSpan {
    SP_GENERATED_BODY()
    SPPROPERTY() double Length = 0.0;
};
} // namespace second
