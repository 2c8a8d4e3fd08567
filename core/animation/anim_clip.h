#pragma once
// An animation clip (UE's UAnimSequence): keyframes of some bones' local transforms over time, sampled at
// any time between them: translations and scales linearly, rotations spherically (slerp), as glTF's LINEAR
// interpolation specifies. A bone without keys keeps its bind pose.

#include <string>
#include <vector>

#include "core/animation/skeleton.h"

namespace sp::animation {

template <typename T> struct Keys {
    std::vector<double> times; // seconds, increasing
    std::vector<T> values;
};

struct BoneTrack {
    int bone = -1; // index into the skeleton the clip is for
    Keys<Eigen::Vector3d> translations;
    Keys<Eigen::Quaterniond> rotations;
    Keys<Eigen::Vector3d> scales;
};

struct AnimClip {
    std::string name;
    double duration = 0.0; // seconds
    std::vector<BoneTrack> tracks;

    // Checks keys (sorted, finite, one value per time) and bone indices against `skeleton`; throws
    // sp::InvalidArgument "<function>(): <what>".
    void validate(const Skeleton& skeleton, const char* function) const;
    // The pose at `time` (clamped to [0, duration]): the bind pose, with every tracked bone's keys
    // interpolated.
    Pose sample(const Skeleton& skeleton, double time) const;
};

// The pose `weight` of the way from `a` to `b` (interpolate() per bone); 0 is `a`, 1 is `b`.
Pose blend(const Pose& a, const Pose& b, double weight);

} // namespace sp::animation
