#include "array_tools.h"

#include <vector>

AArrayTools::AArrayTools() {
    SpFuncComponent = SpUtils::createComponent<USpFuncComponent>(this, "array_tools");

    // Every array, object and the info string come back as they came: in-process without a copy.
    SpFuncComponent->registerFunc("echo", [this](SpFuncDataBundle& args) -> SpFuncDataBundle {
        ++CallCount;
        return std::move(args);
    });

    SpFuncComponent->registerFunc("invert", [this](SpFuncDataBundle& args) -> SpFuncDataBundle {
        ++CallCount;
        SpArray<uint8_t> image("image");
        SpUtils::moveFromPackedArrays({image.getPtr()}, std::move(args.packed_arrays_));
        SpArray<uint8_t> inverted("image");
        // resize() allocates from the current allocator: over RPC, straight in the reply's shared memory.
        inverted.resize(image.getShape());
        const auto in = image.getView();
        const auto out = inverted.getView();
        for (size_t i = 0; i < in.size(); ++i)
            out[i] = uint8_t(255 - in[i]);
        SpFuncDataBundle result;
        result.packed_arrays_ = SpUtils::moveToPackedArrays({inverted.getPtr()});
        result.info_ = "inverted " + image.describeShape();
        return result;
    });
}
