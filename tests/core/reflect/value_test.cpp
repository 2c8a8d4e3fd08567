#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/reflect/codec.h"
#include "core/world/math.h"
#include "core/world/scene_component.h"

using namespace sp::reflect;

namespace {
template <typename F> void expectInvalid(F&& call, const char* message) {
    try {
        call();
        FAIL() << "no error; expected: " << message;
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), message);
    }
}
} // namespace

TEST(Value, KindsAndRepr) {
    EXPECT_EQ(Value().kindName(), "None");
    EXPECT_EQ(Value(int64_t(3)).repr(), "3");
    EXPECT_EQ(Value("abc").repr(), "'abc'");
    EXPECT_EQ(Value(Value::Dict{{"X", Value(1.5)}}).repr(), "{'X': 1.5}");
    EXPECT_EQ(Value(ObjectHandle{5, 2}).repr(), "<object 5:2>");
}

TEST(Value, ArraysCompareByContent) {
    auto a = std::make_shared<std::vector<float>>(std::vector<float>{1, 2, 3});
    auto b = std::make_shared<std::vector<float>>(std::vector<float>{1, 2, 3});
    ArrayValue x{DType::Float32, {3}, a, a->data()};
    ArrayValue y{DType::Float32, {3}, b, b->data()};
    EXPECT_EQ(Value(x), Value(y));
    (*b)[2] = 4;
    EXPECT_NE(Value(x), Value(y));
}

TEST(Codec, ScalarsAreChecked) {
    EXPECT_EQ(decode<int32_t>(Value(int64_t(-4)), "x"), -4);
    EXPECT_EQ(decode<double>(Value(int64_t(2)), "x"), 2.0);
    EXPECT_THROW(decode<uint8_t>(Value(int64_t(300)), "x"), sp::InvalidArgument);
    try {
        decode<bool>(Value("yes"), "F(): argument 'b'");
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "F(): argument 'b' must be a bool, got str 'yes'");
    }
}

TEST(Codec, StructsRoundTripThroughDicts) {
    sp::engine::registerEngineTypes();
    FTransform t{{1, 2, 3}, {0, 0, 0, 1}, {2, 2, 2}};
    Value v = encode(t);
    ASSERT_TRUE(v.is<Value::Dict>());
    EXPECT_EQ(v.as<Value::Dict>().at("Translation").as<Value::Dict>().at("Y").as<double>(), 2.0);
    EXPECT_EQ(decode<FTransform>(v, "t"), t);
    // Missing fields keep their defaults; unknown fields are errors.
    EXPECT_EQ(decode<FVector>(Value(Value::Dict{{"Z", Value(1.0)}}), "v"), (FVector{0, 0, 1}));
    EXPECT_THROW(decode<FVector>(Value(Value::Dict{{"W", Value(1.0)}}), "v"), sp::InvalidArgument);
}

TEST(Codec, EnumsAreValidated) {
    sp::engine::registerEngineTypes();
    EXPECT_EQ(decode<EComponentMobility>(Value(EnumValue{"EComponentMobility", 2}), "m"),
              EComponentMobility::Movable);
    EXPECT_EQ(encode(EComponentMobility::Movable), Value(EnumValue{"EComponentMobility", 2}));
    EXPECT_THROW(decode<EComponentMobility>(Value(EnumValue{"EComponentMobility", 9}), "m"),
                 sp::InvalidArgument);
    // A bare int, or another enum's value, is not an EComponentMobility: both transports refuse it.
    expectInvalid([] { decode<EComponentMobility>(Value(int64_t(2)), "m"); },
                  "m must be EComponentMobility, got int 2");
    expectInvalid(
        [] {
            decode<EComponentMobility>(Value(EnumValue{"ESplineCoordinateSpace", 1}), "m");
        },
        "m must be EComponentMobility, got ESplineCoordinateSpace ESplineCoordinateSpace.World");
    EXPECT_EQ(StaticEnum<EComponentMobility>().nameOf(0), "Static");
}

TEST(Codec, ContainersReportTheBadElement) {
    try {
        decode<std::vector<std::string>>(Value(Value::List{Value("a"), Value(1.0)}), "tags");
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "tags[1] must be a str, got float 1");
    }
    // Each element's name is built on the last one's (one reused string): a two-digit index after one-digit
    // ones, and a nested list's element after a longer name, come out whole.
    Value::List names(11, Value("a"));
    names[10] = Value(int64_t(7));
    try {
        decode<std::vector<std::string>>(Value(names), "tags");
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "tags[10] must be a str, got int 7");
    }
    Value::List rows(12, Value(Value::List{Value(1.0)}));
    rows[11] = Value(Value::List{Value(1.0), Value("x")});
    try {
        decode<std::vector<std::vector<double>>>(Value(rows), "rows");
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "rows[11][1] must be a float, got str 'x'");
    }
}

TEST(SpArray, ShapesAndViews) {
    SpArray<double> a("input");
    a.setDataSource({1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, {-1, 3});
    EXPECT_EQ(a.getShape(), (std::vector<int64_t>{2, 3}));
    EXPECT_EQ(a.getView()[4], 5.0);
    EXPECT_THROW(a.setDataSource({1.0, 2.0}, {3}), sp::InvalidArgument);
    SpArray<float> b("b");
    EXPECT_THROW(b.assign(a.value(), "F()"), sp::InvalidArgument);
}

// A TypedDict struct registered by hand as the generator registers one: complete (every key promised to
// Python) or partial (SPSTRUCT(TypedDict, Partial)).
template <bool Complete> struct FArrayResult {
    SpArray<float> Values;

    static const TypeInfo& StaticClass() {
        static const TypeInfo info = [] {
            TypeInfo t;
            t.name = Complete ? "FCompleteResult" : "FPartialResult";
            t.kind = TypeInfo::Kind::Struct;
            t.isCompleteDict = Complete;
            t.properties.push_back(
                {"Values", TypeCode(TypeCode::Kind::Array, "float32"), "", false,
                 [](const void* self) { return encode(static_cast<const FArrayResult*>(self)->Values); }});
            return t;
        }();
        return info;
    }
};

TEST(Codec, CompleteTypedDictsMustHaveEveryArray) {
    FArrayResult<true> complete;
    try {
        encode(complete);
        FAIL() << "an unset field of a complete TypedDict must not be left out silently";
    } catch (const sp::InvalidState& e) {
        EXPECT_NE(std::string(e.what()).find("FCompleteResult.Values was not set"), std::string::npos)
            << e.what();
    }
    complete.Values.setDataSource(std::vector<float>{1, 2});
    EXPECT_TRUE(encode(complete).as<Value::Dict>().contains("Values"));
    // An empty array is set: only an array that was never given data is missing.
    complete.Values.setDataSource(std::vector<float>{});
    EXPECT_TRUE(encode(complete).as<Value::Dict>().contains("Values"));
}

TEST(Codec, ResultChecksNameTheFunction) {
    FArrayResult<true> complete;
    try {
        checkResultFields(complete, "AMeasurer.Measure()");
        FAIL() << "an unset field of a complete TypedDict result must be reported";
    } catch (const sp::InvalidState& e) {
        EXPECT_EQ(std::string(e.what()).rfind("AMeasurer.Measure(): FCompleteResult.Values was not set", 0),
                  0u)
            << e.what();
    }
    const FArrayResult<false> partial;
    checkResultFields(partial, "AMeasurer.MeasureSome()"); // partial: nothing to check
}

TEST(Codec, PartialTypedDictsLeaveUnsetArraysOut) {
    FArrayResult<false> partial;
    EXPECT_TRUE(encode(partial).as<Value::Dict>().empty());
    partial.Values.setDataSource(std::vector<float>{1, 2});
    EXPECT_TRUE(encode(partial).as<Value::Dict>().contains("Values"));
}
