#include "core/animation/anim_clip.h"

#include <algorithm>
#include <cmath>

#include "core/base/error.h"

namespace sp::animation {
namespace {

template <typename T> void checkKeys(const Keys<T>& keys, const std::string& what, const char* function) {
    SP_CHECK(keys.times.size() == keys.values.size(), InvalidArgument, function, "(): ", what, " has ",
             keys.times.size(), " key times and ", keys.values.size(), " values");
    for (std::size_t k = 0; k < keys.times.size(); ++k) {
        SP_CHECK(std::isfinite(keys.times[k]) && (k == 0 || keys.times[k] >= keys.times[k - 1]),
                 InvalidArgument, function, "(): ", what, "'s key times must be finite and increasing, got ",
                 keys.times[k], " at key ", k);
        if constexpr (std::is_same_v<T, Eigen::Quaterniond>)
            SP_CHECK(keys.values[k].coeffs().allFinite() && keys.values[k].norm() > 1e-9, InvalidArgument,
                     function, "(): ", what, " has a rotation key that is not finite or is zero, at key ", k);
        else
            SP_CHECK(keys.values[k].allFinite(), InvalidArgument, function, "(): ", what,
                     " has a key that is not finite, at key ", k);
    }
}

// The keys' value at `time`: the first before the first key, the last after the last, else interpolated
// between the two keys around it by `mix`.
template <typename T, typename Mix> T sampleKeys(const Keys<T>& keys, double time, Mix mix) {
    const auto after = std::upper_bound(keys.times.begin(), keys.times.end(), time);
    if (after == keys.times.begin())
        return keys.values.front();
    if (after == keys.times.end())
        return keys.values.back();
    const std::size_t k = std::size_t(after - keys.times.begin());
    const double span = keys.times[k] - keys.times[k - 1];
    const double weight = span > 0.0 ? (time - keys.times[k - 1]) / span : 1.0;
    return mix(keys.values[k - 1], keys.values[k], weight);
}

} // namespace

void AnimClip::validate(const Skeleton& skeleton, const char* function) const {
    SP_CHECK(std::isfinite(duration) && duration >= 0.0, InvalidArgument, function, "(): clip '", name,
             "' has duration ", duration);
    for (const BoneTrack& track : tracks) {
        SP_CHECK(track.bone >= 0 && std::size_t(track.bone) < skeleton.size(), InvalidArgument, function,
                 "(): clip '", name, "' animates bone ", track.bone, " of a skeleton of ", skeleton.size());
        const std::string what =
            "clip '" + name + "', bone '" + skeleton.names[std::size_t(track.bone)] + "'";
        checkKeys(track.translations, what, function);
        checkKeys(track.rotations, what, function);
        checkKeys(track.scales, what, function);
    }
}

Pose AnimClip::sample(const Skeleton& skeleton, double time) const {
    time = std::clamp(time, 0.0, duration);
    Pose pose = skeleton.bindLocal;
    for (const BoneTrack& track : tracks) {
        BoneTransform& bone = pose[std::size_t(track.bone)];
        auto lerp = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double w) -> Eigen::Vector3d {
            return a + w * (b - a);
        };
        if (!track.translations.times.empty())
            bone.translation = sampleKeys(track.translations, time, lerp);
        if (!track.rotations.times.empty())
            bone.rotation =
                sampleKeys(track.rotations, time,
                           [](const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double w) {
                               return Eigen::Quaterniond(a.slerp(w, b).normalized());
                           });
        if (!track.scales.times.empty())
            bone.scale = sampleKeys(track.scales, time, lerp);
    }
    return pose;
}

Pose blend(const Pose& a, const Pose& b, double weight) {
    SP_CHECK(a.size() == b.size(), InvalidArgument, "blend(): poses of ", a.size(), " and ", b.size(),
             " bones");
    Pose out(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        out[i] = interpolate(a[i], b[i], weight);
    return out;
}

} // namespace sp::animation
