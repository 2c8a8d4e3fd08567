// expect: tests/codegen/negative/unknown_specifier.h:9: error: malformed SPFUNCTION(BlueprintCalable) on 'Go': unknown specifier 'BlueprintCalable' (known: BlueprintCallable, BlueprintPure, CallInEditor, Category, DeterminesOutputType, DisplayName, NotNull, ToolTip)
#include "core/world/actor.h"

UCLASS()
class AUnknownSpecifier : public AActor {
    GENERATED_BODY()
public:
    /// Goes.
    UFUNCTION(BlueprintCalable) void Go();
};
