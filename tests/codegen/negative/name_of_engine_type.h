// expect: tests/codegen/negative/name_of_engine_type.h:9: error: 'AStaticMeshActor' is already the name of a reflected type in core/world/static_mesh_actor.h; reflected names are global (rename one)
#include "core/world/static_mesh_actor.h"

// A plugin's class in its own namespace is valid C++, but the registry and the Python API know types by
// their unqualified name only.
namespace my_plugin {

SPCLASS()
class AStaticMeshActor : public ::AStaticMeshActor {
    SP_GENERATED_BODY()
};

} // namespace my_plugin
