#include "measurer.h"

#include <map>
#include <vector>

namespace {

std::map<float, int64_t> histogram(const SpArray<float>& samples) {
    std::map<float, int64_t> counts;
    for (float x : samples.getView())
        ++counts[x];
    return counts;
}

std::vector<float> keys(const std::map<float, int64_t>& counts) {
    std::vector<float> result;
    for (const auto& [value, count] : counts)
        result.push_back(value);
    return result;
}

std::vector<int64_t> values(const std::map<float, int64_t>& counts) {
    std::vector<int64_t> result;
    for (const auto& [value, count] : counts)
        result.push_back(count);
    return result;
}

} // namespace

FMeasurement AMeasurer::Measure(const SpArray<float>& Samples) {
    const auto counts = histogram(Samples);
    FMeasurement result;
    result.Values.setDataSource(keys(counts));
    result.Counts.setDataSource(values(counts));
    return result;
}

FPartialMeasurement AMeasurer::MeasureSome(const SpArray<float>& Samples, bool bCount) {
    const auto counts = histogram(Samples);
    FPartialMeasurement result;
    result.Values.setDataSource(keys(counts));
    if (bCount)
        result.Counts.setDataSource(values(counts));
    return result;
}

FMeasurement AMeasurer::MeasureForgetful(const SpArray<float>& Samples) {
    FMeasurement result;
    result.Values.setDataSource(keys(histogram(Samples)));
    return result;
}
