#pragma once
// The SPEAR paper's Fig. 8, unchanged except for the include line: an actor with a USpFuncComponent whose
// SpFunc "my_sp_func" takes an array named "input" and returns one named "output".

#include "core/spfunc/spfunc.h"

UCLASS()
class AMyActor : public AActor {
    GENERATED_BODY()
public:
    AMyActor() {
        // create USpFuncComponent and attach to this actor
        SpFuncComponent = SpUtils::createComponent<USpFuncComponent>(this, "my_sp_func_component");
    }

    UFUNCTION(BlueprintCallable)
    void Initialize() {
        SpFuncComponent->registerFunc("my_sp_func", [this](SpFuncDataBundle& args) -> SpFuncDataBundle {

            // unpack argument
            SpArray<double> input("input");
            SpUtils::moveFromPackedArrays({input.getPtr()}, std::move(args.packed_arrays_));

            // process argument
            const std::span<double>& view = input.getView();
            SP_LOG("Input is [" , view[0], " , " , view[1], " , " , view[2], "]" );

            // prepare return value
            SpArray<double> output("output");
            output.setDataSource({4.0, 5.0, 6.0});

            // pack return value
            SpFuncDataBundle return_values;
            return_values.packed_arrays_ = SpUtils::moveToPackedArrays({output.getPtr()});
            return return_values;
        });
    }

    UFUNCTION(BlueprintCallable)
    void Terminate() {
        SpFuncComponent->unregisterFunc("my_sp_func");
    }

    UPROPERTY(VisibleAnywhere)
    USpFuncComponent* SpFuncComponent = nullptr;
};
