#include "array_tools.h"

#include <vector>

#include "core/world/math.h"

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

    // Objects travel beside the arrays as JSON: an FVector in, an FVector out.
    SpFuncComponent->registerFunc("center_points", [this](SpFuncDataBundle& args) -> SpFuncDataBundle {
        ++CallCount;
        SpArray<double> points("points");
        SpUtils::moveFromPackedArrays({points.getPtr()}, std::move(args.packed_arrays_));
        points.checkShape({-1, 3}, "AArrayTools.center_points(): array 'points'");
        const FVector origin = SpUtils::getUnrealObj<FVector>(args, "origin");
        const auto in = points.getView();
        std::vector<double> shifted(in.size());
        FVector centroid{0, 0, 0};
        const size_t count = in.size() / 3;
        for (size_t i = 0; i < count; ++i) {
            shifted[3 * i] = in[3 * i] - origin.X;
            shifted[3 * i + 1] = in[3 * i + 1] - origin.Y;
            shifted[3 * i + 2] = in[3 * i + 2] - origin.Z;
            centroid.X += shifted[3 * i] / double(count);
            centroid.Y += shifted[3 * i + 1] / double(count);
            centroid.Z += shifted[3 * i + 2] / double(count);
        }
        SpArray<double> result("points");
        result.setDataSource(std::move(shifted), {-1, 3});
        SpFuncDataBundle out;
        out.packed_arrays_ = SpUtils::moveToPackedArrays({result.getPtr()});
        SpUtils::setUnrealObj(out, "centroid", centroid);
        return out;
    });

    // Arrays an SpFunc keeps outlive the call: "store" keeps its arrays, "recall" returns them.
    SpFuncComponent->registerFunc("store", [this](SpFuncDataBundle& args) -> SpFuncDataBundle {
        ++CallCount;
        stored_ = std::move(args.packed_arrays_);
        return {};
    });
    SpFuncComponent->registerFunc("recall", [this](SpFuncDataBundle&) -> SpFuncDataBundle {
        ++CallCount;
        SpFuncDataBundle result;
        result.packed_arrays_ = stored_;
        return result;
    });
}
