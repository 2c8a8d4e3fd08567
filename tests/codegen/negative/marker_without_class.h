// expect: tests/codegen/negative/marker_without_class.h:4: error: SPCLASS() must be followed by a class definition
#include "core/world/actor.h"

SPCLASS()
void NotAClass();
