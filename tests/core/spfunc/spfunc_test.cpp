#include <gtest/gtest.h>

#include "core/engine/engine.h"
#include "core/spfunc/sp_func_call.h"
#include "core/spfunc/spfunc.h"
#include "core/world/scene_component.h"

namespace {
// Fig. 8's SpFunc, registered on a component created at run time.
SpFuncDataBundle addThree(SpFuncDataBundle& args) {
    SpArray<double> input("input");
    SpUtils::moveFromPackedArrays({input.getPtr()}, std::move(args.packed_arrays_));
    SpArray<double> output("output");
    std::vector<double> values;
    for (double v : input.getView())
        values.push_back(v + 3.0);
    output.setDataSource(std::move(values), input.getShape());
    SpFuncDataBundle result;
    result.packed_arrays_ = SpUtils::moveToPackedArrays({output.getPtr()});
    result.unreal_obj_strings_ = args.unreal_obj_strings_;
    result.info_ = "got " + args.info_;
    return result;
}

SpPackedArray doubles(std::vector<double> values) {
    SpArray<double> array("x");
    array.setDataSource(std::move(values));
    return array.value();
}

struct SpFuncTest : ::testing::Test {
    sp::engine::Engine engine;
    AActor* actor = engine.GetGameWorld().spawn_actor(&AActor::StaticClass());
    USpFuncComponent* component = SpUtils::createComponent<USpFuncComponent>(actor, "sp_funcs");

    std::string errorOf(const std::function<void()>& f) {
        try {
            f();
        } catch (const sp::Error& e) {
            return e.what();
        }
        return "";
    }
};
} // namespace

TEST_F(SpFuncTest, CallsReachTheActorsComponentAndArraysKeepTheirShape) {
    component->registerFunc("add_three", &addThree);
    EXPECT_EQ(sp::spfunc::funcNames(*actor), std::vector<std::string>{"add_three"});
    SpFuncDataBundle args;
    args.packed_arrays_["input"] = doubles({1, 2, 3, 4, 5, 6});
    args.packed_arrays_["input"].shape = {2, 3};
    args.unreal_obj_strings_["pose"] = R"({"X": 1.0})";
    args.info_ = "hello";
    SpFuncDataBundle result = sp::spfunc::call(*actor, "add_three", std::move(args));
    const SpPackedArray& output = result.packed_arrays_.at("output");
    EXPECT_EQ(output.shape, (std::vector<int64_t>{2, 3}));
    EXPECT_EQ(static_cast<const double*>(output.data)[5], 9.0);
    EXPECT_EQ(result.unreal_obj_strings_.at("pose"), R"({"X": 1.0})");
    EXPECT_EQ(result.info_, "got hello");
    // The component answers directly, too.
    EXPECT_EQ(sp::spfunc::funcNames(*component), std::vector<std::string>{"add_three"});
}

TEST_F(SpFuncTest, BadArraysNameTheSpFuncAndTheArray) {
    component->registerFunc("add_three", &addThree);
    SpFuncDataBundle wrongDtype;
    SpArray<float> floats("input");
    floats.setDataSource({1.0f, 2.0f});
    wrongDtype.packed_arrays_["input"] = floats.value();
    EXPECT_EQ(errorOf([&] { sp::spfunc::call(*actor, "add_three", wrongDtype); }),
              "AActor.add_three(): array 'input' must have dtype float64, got float32");
    SpFuncDataBundle misspelt;
    misspelt.packed_arrays_["inptu"] = doubles({1});
    EXPECT_EQ(errorOf([&] { sp::spfunc::call(*actor, "add_three", misspelt); }),
              "AActor.add_three(): array 'input' was not passed (got 'inptu')");
}

TEST_F(SpFuncTest, UnknownNamesListWhatThereIsAndUnregisterRemoves) {
    component->registerFunc("add_three", &addThree);
    EXPECT_EQ(errorOf([&] { sp::spfunc::call(*actor, "add_tree", {}); }),
              "AActor.add_tree(): AActor 'Actor_0' has no SpFunc named 'add_tree' (it has 'add_three')");
    EXPECT_THROW(component->registerFunc("add_three", &addThree), sp::InvalidArgument);
    component->unregisterFunc("add_three");
    EXPECT_TRUE(sp::spfunc::funcNames(*actor).empty());
    EXPECT_THROW(component->unregisterFunc("add_three"), sp::NotFound);
    EXPECT_THROW(sp::spfunc::call(*actor, "add_three", {}), sp::NotFound);
}

TEST_F(SpFuncTest, AnSpFuncMayUnregisterItselfWhileItRuns) {
    component->registerFunc("once", [this](SpFuncDataBundle&) {
        component->unregisterFunc("once");
        return SpFuncDataBundle{};
    });
    sp::spfunc::call(*actor, "once", {});
    EXPECT_TRUE(component->GetFuncNames().empty());
}

TEST_F(SpFuncTest, BundlesRoundTripThroughValues) {
    SpFuncDataBundle bundle;
    bundle.packed_arrays_["a"] = doubles({1, 2});
    bundle.unreal_obj_strings_["o"] = "{}";
    bundle.info_ = "i";
    SpFuncDataBundle back = sp::spfunc::bundleFromValue(sp::spfunc::toValue(bundle), "test");
    EXPECT_EQ(back.packed_arrays_.at("a"), bundle.packed_arrays_.at("a"));
    EXPECT_EQ(back.unreal_obj_strings_, bundle.unreal_obj_strings_);
    EXPECT_EQ(back.info_, "i");
    EXPECT_THROW(
        sp::spfunc::bundleFromValue(sp::reflect::Value(sp::reflect::Value::Dict{{"arrayz", {}}}), "t"),
        sp::InvalidArgument);
}

TEST_F(SpFuncTest, ObjectsAreReadAndWrittenAsReflectedTypes) {
    SpFuncDataBundle bundle;
    bundle.unreal_obj_strings_["pose"] = R"({"X": 1, "Y": 2.5, "Z": -3})"; // Python may send 1 for 1.0
    const FVector pose = SpUtils::getUnrealObj<FVector>(bundle, "pose");
    EXPECT_EQ(pose.X, 1.0);
    EXPECT_EQ(pose.Y, 2.5);
    EXPECT_EQ(pose.Z, -3.0);
    SpUtils::setUnrealObj(bundle, "out", FVector{1.0, 2.0, 3.0});
    EXPECT_EQ(bundle.unreal_obj_strings_.at("out"), R"({"X":1.0,"Y":2.0,"Z":3.0})");
    SpUtils::setUnrealObj(bundle, "names", std::vector<std::string>{"a", "b"});
    EXPECT_EQ(SpUtils::getUnrealObj<std::vector<std::string>>(bundle, "names"),
              (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(errorOf([&] { SpUtils::getUnrealObj<FVector>(bundle, "nope"); }),
              "SpUtils::getUnrealObj(): object 'nope' was not passed (got 'names', 'out', 'pose')");
    // JSON has no enums: an enum travels as its int (as Python's json writes an IntEnum), both ways.
    SpUtils::setUnrealObj(bundle, "mobility", EComponentMobility::Movable);
    EXPECT_EQ(bundle.unreal_obj_strings_.at("mobility"), "2");
    EXPECT_EQ(SpUtils::getUnrealObj<EComponentMobility>(bundle, "mobility"), EComponentMobility::Movable);
    bundle.unreal_obj_strings_["mobilities"] = "[0, 2]";
    EXPECT_EQ(SpUtils::getUnrealObj<std::vector<EComponentMobility>>(bundle, "mobilities"),
              (std::vector<EComponentMobility>{EComponentMobility::Static, EComponentMobility::Movable}));
    bundle.unreal_obj_strings_["mobility"] = "7";
    EXPECT_THROW(SpUtils::getUnrealObj<EComponentMobility>(bundle, "mobility"), sp::InvalidArgument);
    bundle.unreal_obj_strings_["bad"] = "{not json";
    EXPECT_THROW(SpUtils::getUnrealObj<FVector>(bundle, "bad"), sp::InvalidArgument);
    // Inside an SpFunc, errors name it.
    component->registerFunc("read", [](SpFuncDataBundle& args) {
        SpUtils::getUnrealObj<FVector>(args, "origin");
        return SpFuncDataBundle{};
    });
    EXPECT_EQ(errorOf([&] { sp::spfunc::call(*actor, "read", {}); }),
              "AActor.read(): object 'origin' was not passed (got no objects)");
}

TEST_F(SpFuncTest, WhatAnSpFuncThrowsBecomesAnEngineErrorNamingIt) {
    component->registerFunc("throws", [](SpFuncDataBundle& args) {
        args.packed_arrays_.at("missing"); // std::out_of_range
        return SpFuncDataBundle{};
    });
    try {
        sp::spfunc::call(*actor, "throws", {});
        FAIL() << "no exception";
    } catch (const sp::Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("AActor.throws(): ", 0), 0u) << e.what();
    }
    // The engine is fine: the next call runs.
    component->registerFunc("fine", [](SpFuncDataBundle&) { return SpFuncDataBundle{}; });
    EXPECT_NO_THROW(sp::spfunc::call(*actor, "fine", {}));
}
