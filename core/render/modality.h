#pragma once
// The camera sensor's ground-truth modalities: names, dtypes and shapes, sets of them, and which render
// passes a set needs. Pure logic, no GL.
//
// | modality             | dtype, shape        | meaning                                                 |
// |----------------------|---------------------|---------------------------------------------------------|
// | final_color          | uint8 (H,W,4)       | tone-mapped sRGB, alpha 255                             |
// | hdr_color            | float16 (H,W,4)     | linear HDR radiance before exposure and tone mapping    |
// | depth                | float32 (H,W)       | metres along the optical axis (camera +X); 0 background |
// | position             | float32 (H,W,3)     | world space; 0 background                               |
// | normal               | float32 (H,W,3)     | world space, unit, facing the camera; 0 background      |
// | object_ids           | uint32 (H,W)        | caller's per-slot id; 0 background                      |
// | material_ids         | uint32 (H,W)        | Material::id (default handle index + 1); 0 background   |
// | base_color           | float16 (H,W,3)     | linear base colour                                      |
// | roughness, metallic, material_ao | float16 (H,W) | PBR inputs                                    |
// | diffuse_illumination | float16 (H,W,3)     | radiance of a white Lambertian surface at the pixel     |
// | diffuse_only         | float16 (H,W,3)     | base_color * (1 - metallic) * diffuse_illumination      |
// | specular_residual    | float16 (H,W,3)     | hdr_color.rgb - diffuse_only (specular, emission, sky)  |

#include <bitset>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sp::render {

// The modalities, listed once: enumerator, name (read_pixels()'s key), element type (DType) and channels.
// Modality, its table (modalityInfo()) and kModalityCount are made from this list; the engine's reflected
// ECameraModality and FCameraPixels, which the generator must read as plain declarations, are checked against
// it entry by entry at compile time (core/sensors/render_subsystem.cpp), so a modality added here and not
// there (or the other way round) fails the build naming it.
#define SP_RENDER_MODALITIES(X)                                                                              \
    X(FinalColor, final_color, UInt8, 4)                                                                     \
    X(HdrColor, hdr_color, Float16, 4)                                                                       \
    X(Depth, depth, Float32, 1)                                                                              \
    X(Position, position, Float32, 3)                                                                        \
    X(Normal, normal, Float32, 3)                                                                            \
    X(ObjectIds, object_ids, UInt32, 1)                                                                      \
    X(MaterialIds, material_ids, UInt32, 1)                                                                  \
    X(BaseColor, base_color, Float16, 3)                                                                     \
    X(Roughness, roughness, Float16, 1)                                                                      \
    X(Metallic, metallic, Float16, 1)                                                                        \
    X(MaterialAo, material_ao, Float16, 1)                                                                   \
    X(DiffuseIllumination, diffuse_illumination, Float16, 3)                                                 \
    X(DiffuseOnly, diffuse_only, Float16, 3)                                                                 \
    X(SpecularResidual, specular_residual, Float16, 3)

enum class Modality : std::uint8_t {
#define SP_MODALITY_ENUMERATOR(enumerator, name, dtype, channels) enumerator,
    SP_RENDER_MODALITIES(SP_MODALITY_ENUMERATOR)
#undef SP_MODALITY_ENUMERATOR
};
#define SP_MODALITY_ONE(enumerator, name, dtype, channels) +1
inline constexpr std::size_t kModalityCount = 0 SP_RENDER_MODALITIES(SP_MODALITY_ONE);
#undef SP_MODALITY_ONE

enum class DType : std::uint8_t { UInt8, UInt32, Float16, Float32 };

// Static description of one modality.
struct ModalityInfo {
    Modality modality;
    std::string_view name; // snake_case, as in the design's table
    DType dtype;
    int channels; // 1 means shape (H,W); otherwise (H,W,channels)
};

const ModalityInfo& modalityInfo(Modality modality);
std::string_view modalityName(Modality modality);
std::size_t dtypeSize(DType dtype);
std::string_view dtypeName(DType dtype);
// Bytes of one (height, width) image of the modality, tightly packed, row 0 = top row.
std::size_t modalityByteSize(Modality modality, int width, int height);
// Throws sp::NotFound "modalityFromName(): unknown modality 'x' (known: ...)".
Modality modalityFromName(std::string_view name);

// The colour targets a frame can write, each one texture of the camera's framebuffers.
// Formats are the float ones; compact targets (PassSet::compactTargets) hold the float16 ones' bits in
// RGBA16UI and the normal in RG32F (octahedral).
enum class Target : std::uint8_t {
    Position,            // RGBA32F world position, w = 1 on geometry (0 = background)
    Normal,              // RGBA32F world normal
    Depth,               // R32F metres along the optical axis
    BaseColor,           // RGBA16F
    Params,              // RGBA16F roughness, metallic, ao
    Ids,                 // RG32UI object id, material id
    Hdr,                 // RGBA16F linear radiance
    DiffuseIllumination, // RGBA16F
    DiffuseOnly,         // RGBA16F
    SpecularResidual,    // RGBA16F
    FinalColor,          // RGBA8 tone-mapped sRGB
    // R32UI: 1 + the index of the draw whose surface the pixel shows, in the view's draw list; 0 where none.
    // The material modalities are looked up from it (ModalityPlan::lookedUp). No modality.
    Record,
    // R32UI: the octahedral shading normal and the draw's InstanceRecord (shaders::kGBufferChunk); a surface
    // pass whose shading runs in a compute pass writes it instead of shading (PassSet::computeLighting()).
    // No modality.
    GBuffer,
    // RG32UI: a textured material's base colour, roughness and metallic at the pixel (shaders::
    // kGBufferMaterialChunk), written beside Target::GBuffer by a textured draw whose shading runs in the
    // compute pass; read there where the draw's record says so. No modality.
    GBufferMaterial,
};
inline constexpr std::size_t kTargetCount = 14;
using TargetMask = std::uint32_t;
inline constexpr TargetMask targetBit(Target target) {
    return TargetMask(1) << static_cast<unsigned>(target);
}
// The targets of float16 modalities (RGBA16F, or RGBA16UI when compact).
inline constexpr TargetMask kHalfTargets = targetBit(Target::BaseColor) | targetBit(Target::Params) |
                                           targetBit(Target::Hdr) | targetBit(Target::DiffuseIllumination) |
                                           targetBit(Target::DiffuseOnly) |
                                           targetBit(Target::SpecularResidual);
// The targets only a shading pass writes: colour and the intrinsic images.
inline constexpr TargetMask kShadedTargets =
    targetBit(Target::Hdr) | targetBit(Target::DiffuseIllumination) | targetBit(Target::DiffuseOnly) |
    targetBit(Target::SpecularResidual) | targetBit(Target::FinalColor);
// The target a modality is read from (roughness, metallic and AO share Params; both id kinds share Ids).
Target targetOf(Modality modality);
std::string_view targetName(Target target);

// The draw buffers every OpenGL 4.5 context has (GL_MAX_DRAW_BUFFERS is at least 8).
inline constexpr int kMaxDrawTargets = 8;

// The render passes a modality set needs; only these run. Shading is forward: the surface pass shades
// every fragment where it is rasterised (lights, shadows, sky, tone curve, sRGB) and writes the requested
// targets beside the colour. A set with more targets than one pass can write (all 14 modalities need 11)
// has the rest written by an attribute pass: the same geometry drawn again against the surface pass's
// depth (equal depth, no writes), so only the visible fragment of each pixel runs its shader.
struct PassSet {
    bool shadow = false;             // shadow maps (only when shading runs and the camera enables shadows)
    bool surface = false;            // the surface pass (geometry rasterisation)
    bool lighting = false;           // the surface pass shades
    bool tonemap = false;            // exposure, tone curve, sRGB encoding (fused into the shading)
    TargetMask surfaceTargets = 0;   // written by the surface pass, attached in Target order
    TargetMask attributeTargets = 0; // written by the attribute pass, attached in Target order
    // The compact encoding (Renderer::compactTargets()): the float16 targets are RGBA16UI holding float16
    // bits (packHalf2x16) and the normal is RG32F, its octahedral coordinates; the readback returns the same
    // values, the normal decoded on the CPU. A software rasteriser stores integers and two channels for far
    // less than float16 conversions and four channels.
    bool compactTargets = false;
    // Coverage samples a pixel of the shaded targets (1: none). Above 1 (multisampled(): CameraParams' MSAA),
    // the surface pass draws only the shaded targets, into multisampled copies of them that it then resolves
    // into them, and the attribute pass draws the other targets single-sampled with a depth buffer of its
    // own: the exact modalities stay one value a pixel, the surface at its centre.
    int samples = 1;
    // Spatial samples a pixel of the shaded targets (1: none; spatiallySampled():
    // CameraParams::spatialSamples). Above 1, the surface pass of spatialSampleSurface(*this) draws the
    // shaded targets once for each sample, with the pixels moved by its offset, into
    // Framebuffers::spatialSampled(), each copied into its layer of Framebuffers::sampleLayers(), which are
    // averaged into these; the attribute pass draws the other targets as with samples above 1. Never with
    // samples above 1: the coverage samples of each moved pass would add their offsets to the sample's and
    // widen a pixel's footprint past its square (blurring it).
    int spatialSamples = 1;

    bool operator==(const PassSet&) const = default;
    // Whether the surface pass writes Target::GBuffer (and, with room for it, Target::GBufferMaterial for
    // textured materials) and a compute pass shades those pixels (Renderer::planComputeLighting() adds them;
    // requiredPasses() never does).
    bool computeLighting() const { return (surfaceTargets & targetBit(Target::GBuffer)) != 0; }
};

// `passes` drawn with `samples` coverage samples a pixel (see PassSet::samples): the shaded targets in the
// surface pass, the others in the attribute pass, in float targets (a multisampled resolve averages floats).
// Passes that shade nothing, or samples of 1, are returned as they are.
PassSet multisampled(PassSet passes, int samples);
// `passes` with their shaded targets drawn with `count` spatial samples a pixel (see
// PassSet::spatialSamples): split as multisampled() splits them. Passes that shade nothing, or a count of 1,
// are returned as they are.
PassSet spatiallySampled(PassSet passes, int count);
// The passes that draw one spatial sample of a spatially sampled PassSet's shaded targets: its surface pass,
// shading only those targets, no attribute pass.
PassSet spatialSampleSurface(PassSet passes);

// What a compact normal target holds where no surface is: outside the octahedral square [-1, 1]^2.
inline constexpr float kNoOctahedralNormal = 2.0f;

class ModalitySet {
  public:
    ModalitySet() = default;
    ModalitySet(std::initializer_list<Modality> modalities);
    static ModalitySet all();
    // Throws sp::NotFound for an unknown name.
    static ModalitySet fromNames(const std::vector<std::string>& names);

    ModalitySet& add(Modality modality);
    ModalitySet& remove(Modality modality);
    bool contains(Modality modality) const { return bits_.test(static_cast<std::size_t>(modality)); }
    bool empty() const { return bits_.none(); }
    std::size_t size() const { return bits_.count(); }
    // In enum order.
    std::vector<Modality> list() const;
    std::vector<std::string> names() const;
    // Passes needed to produce every modality in the set (shadow decided by the caller's camera).
    PassSet requiredPasses(bool shadowsEnabled) const;
    // The targets the set's modalities are read from.
    TargetMask targets() const;

    bool operator==(const ModalitySet&) const = default;

  private:
    std::bitset<kModalityCount> bits_;
};

// How a frame of a modality set is made: the modalities rendered, and those computed on the CPU from them
// (derived_images.h). A software rasteriser pays for every target it writes, so where the set needs more
// targets than one pass can write, diffuse_only and specular_residual are computed from base colour,
// metallic, diffuse illumination and HDR colour instead of rendered, and then, if the set still needs more,
// position from depth and the camera, each when that leaves fewer targets (all 14 modalities: 8 targets
// instead of 11, one pass). A GPU writes targets nearly for free: there (softwareRasteriser false), and for
// smaller sets, everything is rendered.
// A software rasteriser also looks the modalities a draw gives all its pixels (`uniform`: both ids and AO
// always, base colour where no material has a base colour texture, roughness and metallic where none has a
// roughness-metallic texture) up from the draw that left each pixel's surface, which Target::Record names,
// when that writes fewer targets: all 14 modalities then draw 6 targets instead of 8 without textures, 7 with
// either kind (derived_images.h, lookUpMaterials()).
struct ModalityPlan {
    ModalitySet rendered;
    ModalitySet derived;
    ModalitySet lookedUp;        // from the draw's material (Target::Record)
    bool compactTargets = false; // rendered into compact targets (PassSet::compactTargets)
    bool operator==(const ModalityPlan&) const = default;
    // The targets the plan draws: its rendered modalities', and Target::Record for the looked-up ones.
    TargetMask targets() const;
};
ModalityPlan planModalities(const ModalitySet& modalities, bool softwareRasteriser,
                            const ModalitySet& uniform = {});
// The modalities a draw's material gives every pixel of it where no texture varies them
// (ModalityPlan::lookedUp).
ModalitySet materialModalities();

} // namespace sp::render
