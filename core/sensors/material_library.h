#pragma once
// Materials by name. A UStaticMeshComponent names one material per slot (Materials); the world's
// RenderSubsystem resolves each name, first match wins:
//   1. an AMaterialLibrary actor in the world whose Materials map has the name;
//   2. a built-in material (sp::sensors::builtinMaterial(): "Default", "White", "Black", "Grey", "Red",
//      "Green", "Blue", "Yellow", "Wood", "Plaster", "Fabric", "Metal", "Gold", "Plastic", "Mirror",
//      "Emissive", with or without the "/Engine/Materials/" prefix);
//   3. otherwise the default grey material, under the unknown name (logged once), so that it still has
//      its own material id.

#include <map>
#include <string>

#include "core/world/actor.h"

/// A PBR metallic-roughness material (glTF / UE conventions, linear colours).
SPSTRUCT()
struct FMaterialDesc {
    SP_GENERATED_BODY()

    /// Linear RGB base colour (alpha unused: materials are opaque).
    SPPROPERTY()
    FLinearColor BaseColor{0.8f, 0.8f, 0.8f, 1.0f};
    /// Perceptual roughness in [0, 1].
    SPPROPERTY()
    float Roughness = 0.5f;
    /// Metalness in [0, 1].
    SPPROPERTY()
    float Metallic = 0.0f;
    /// Ambient occlusion in [0, 1]; scales the ambient and indirect light only (times OcclusionTexture's R).
    SPPROPERTY()
    float AmbientOcclusion = 1.0f;
    /// Linear RGB radiance emitted by the surface (alpha unused).
    SPPROPERTY()
    FLinearColor Emissive{0.0f, 0.0f, 0.0f, 1.0f};
    /// Path of an sRGB PNG/JPG multiplying BaseColor ("" for none).
    SPPROPERTY()
    std::string BaseColorTexture;
    /// Path of a glTF-layout texture (G = roughness, B = metallic) multiplying the factors ("" for none).
    SPPROPERTY()
    std::string RoughnessMetallicTexture;
    /// Path of a texture whose R channel multiplies AmbientOcclusion, glTF's occlusion map ("" for none):
    /// often the same file as RoughnessMetallicTexture (an ORM map, occlusion in R); a separate one must have
    /// its size. It darkens the ambient and indirect light in crevices too small for the irradiance probes.
    SPPROPERTY()
    std::string OcclusionTexture;
    /// Path of a tangent-space normal map, OpenGL convention ("" for none).
    SPPROPERTY()
    std::string NormalTexture;
    /// Metres one repeat of the textures covers, as UE's WorldAlignedTexture's TextureSize but on the
    /// object's own axes and scale, so that textures keep one size across boxes of any scale and stay on a
    /// moving object: each face takes the plane of the axis it faces. 0 (the default): the mesh's uvs.
    SPPROPERTY()
    float TextureSize = 0.0f;

    friend bool operator==(const FMaterialDesc&, const FMaterialDesc&) = default;
};

/// An actor that defines materials by name for the meshes of its world.
SPCLASS()
class AMaterialLibrary : public AActor {
    SP_GENERATED_BODY()
  public:
    /// Materials by name; mesh components refer to them in their Materials list. Set through
    /// SetMaterials(), which checks every entry as SetMaterial() does.
    SPPROPERTY(Setter = SetMaterials)
    std::map<std::string, FMaterialDesc> Materials;

    /// Replaces every material; raises InvalidArgumentError naming the first entry out of range (none is
    /// changed then).
    SPFUNCTION()
    void SetMaterials(const std::map<std::string, FMaterialDesc>& NewMaterials);

    /// Defines (or replaces) the material called Name.
    SPFUNCTION()
    void SetMaterial(const std::string& Name, const FMaterialDesc& Material);

    /// Returns the material a mesh slot named Name gets: this library's, else the built-in one, else the
    /// default grey one.
    SPFUNCTION()
    FMaterialDesc GetMaterial(const std::string& Name) const;

    /// Returns the names of the built-in materials.
    SPFUNCTION()
    std::vector<std::string> GetBuiltinMaterialNames() const;
};

namespace sp::sensors {

// The built-in material called name (with or without "/Engine/Materials/"), or nullptr.
const FMaterialDesc* builtinMaterial(const std::string& name);
std::vector<std::string> builtinMaterialNames();

// Throws sp::InvalidArgument naming the first field of `material` out of range, after `context`.
void checkMaterial(const FMaterialDesc& material, const std::string& context);

} // namespace sp::sensors
