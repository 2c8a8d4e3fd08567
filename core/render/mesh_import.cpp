#include "core/render/mesh_import.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/progress.h"
#include "core/base/recent_cache.h"
#include "core/base/regular_file.h"
#include "core/render/assimp_reading.h"
#include "core/render/content_key.h"
#include "core/render/mesh_lods.h"

namespace sp::render {
namespace {

// Assimp opens the files a mesh refers to (an OBJ's material library, a glTF's buffers) by path, with
// fopen: one that names a FIFO would block the engine for good. Those go through the same checks as the
// mesh file itself (core/base/regular_file.h); one that fails is reported as missing.
// It also lists them, for the import cache (importMesh()).
class RegularFilesOnly : public Assimp::DefaultIOSystem {
  public:
    explicit RegularFilesOnly(std::vector<std::string>& opened) : opened_(opened) {}
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        if (mode && mode[0] == 'r') {
            opened_.push_back(file);
            try {
                checkRegularFile(file, "importMesh()", "referenced file");
            } catch (const Error& error) {
                SP_LOG(error.what());
                return nullptr;
            }
        }
        return Assimp::DefaultIOSystem::Open(file, mode);
    }

  private:
    std::vector<std::string>& opened_;
};

// What an import reads from: the mesh file's folder (textures are named relative to it), and the files read
// or looked for, for the import cache.
struct Reading {
    std::filesystem::path directory;
    std::vector<std::string> files;
};

std::optional<TextureImage> readTexture(const aiScene* scene, const aiMaterial* material, aiTextureType type,
                                        unsigned index, Reading& reading) {
    aiString path;
    if (material->GetTexture(type, index, &path) != AI_SUCCESS)
        return std::nullopt;
    const std::string name = path.C_Str();
    try {
        if (const aiTexture* embedded = scene->GetEmbeddedTexture(path.C_Str())) {
            if (embedded->mHeight == 0) // compressed (PNG/JPG bytes)
                return TextureImage::decode(reinterpret_cast<const std::uint8_t*>(embedded->pcData),
                                            embedded->mWidth, name);
            std::vector<std::uint8_t> rgba;
            for (unsigned i = 0; i < embedded->mWidth * embedded->mHeight; ++i) {
                const aiTexel& t = embedded->pcData[i];
                rgba.insert(rgba.end(), {t.r, t.g, t.b, t.a});
            }
            return TextureImage::fromPixels(int(embedded->mWidth), int(embedded->mHeight), std::move(rgba));
        }
        reading.files.push_back((reading.directory / name).string()); // looked for, there or not
        return TextureImage::load((reading.directory / name).string());
    } catch (const Error& error) {
        // Assets with broken texture references are common; the material keeps its factors.
        SP_LOG("importMesh(): skipping texture '", name, "': ", error.what());
        return std::nullopt;
    }
}

ImportedMaterial readMaterial(const aiScene* scene, const aiMaterial* source, Reading& reading) {
    ImportedMaterial out;
    out.name = source->GetName().C_Str();
    aiColor4D color;
    if (source->Get(AI_MATKEY_BASE_COLOR, color) == AI_SUCCESS ||
        source->Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS)
        out.material.baseColor = {color.r, color.g, color.b, color.a};
    float value = 0.0f;
    if (source->Get(AI_MATKEY_METALLIC_FACTOR, value) == AI_SUCCESS)
        out.material.metallic = std::clamp(value, 0.0f, 1.0f);
    if (source->Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == AI_SUCCESS)
        out.material.roughness = std::clamp(value, 0.0f, 1.0f);
    else if (source->Get(AI_MATKEY_SHININESS, value) == AI_SUCCESS && value > 0.0f)
        out.material.roughness = std::clamp(std::sqrt(2.0f / (value + 2.0f)), 0.0f, 1.0f); // Phong -> GGX
    aiColor3D emissive;
    if (source->Get(AI_MATKEY_COLOR_EMISSIVE, emissive) == AI_SUCCESS)
        out.material.emissive = {emissive.r, emissive.g, emissive.b};
    out.material.baseColor = out.material.baseColor.cwiseMax(0.0f);
    out.material.emissive = out.material.emissive.cwiseMax(0.0f);

    out.baseColorTexture = readTexture(scene, source, aiTextureType_BASE_COLOR, 0, reading);
    if (!out.baseColorTexture)
        out.baseColorTexture = readTexture(scene, source, aiTextureType_DIFFUSE, 0, reading);
    out.roughnessMetallicTexture =
        readTexture(scene, source, AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_METALLICROUGHNESS_TEXTURE, reading);
    // glTF's occlusion map (assimp's glTF importer files it as a light map), packed into the texture's R.
    std::optional<TextureImage> occlusion =
        readTexture(scene, source, aiTextureType_AMBIENT_OCCLUSION, 0, reading);
    if (!occlusion)
        occlusion = readTexture(scene, source, aiTextureType_LIGHTMAP, 0, reading);
    if (out.roughnessMetallicTexture || occlusion) {
        try {
            out.roughnessMetallicTexture = packOcclusionRoughnessMetallic(
                out.roughnessMetallicTexture ? &*out.roughnessMetallicTexture : nullptr,
                occlusion ? &*occlusion : nullptr);
        } catch (const Error& error) { // maps of two sizes: the material keeps its metallic-roughness map
            SP_LOG("importMesh(): skipping the occlusion map: ", error.what());
            if (out.roughnessMetallicTexture)
                out.roughnessMetallicTexture =
                    packOcclusionRoughnessMetallic(&*out.roughnessMetallicTexture, nullptr);
        }
    }
    out.normalTexture = readTexture(scene, source, aiTextureType_NORMALS, 0, reading);
    return out;
}

} // namespace

namespace {
// Assimp's reading and post-processing, as the fraction it reports (a large file reads for seconds).
class ReportProgress : public Assimp::ProgressHandler {
  public:
    explicit ReportProgress(base::Progress& progress) : progress_(progress) {}
    bool Update(float fraction) override {
        if (fraction >= 0.0f)
            progress_.set(fraction);
        return true; // go on
    }

  private:
    base::Progress& progress_;
};

// A file as an import found it: which file (device, inode), its size and its modification and change times
// to the nanosecond, or its absence.
struct FileStamp {
    std::string path;
    bool exists = false;
    std::array<std::int64_t, 7> identity{};
    bool operator==(const FileStamp&) const = default;
};

FileStamp stampOf(const std::string& path) {
    FileStamp stamp{path};
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0 || !S_ISREG(status.st_mode))
        return stamp;
    stamp.exists = true;
    stamp.identity = {std::int64_t(status.st_dev),          std::int64_t(status.st_ino),
                      std::int64_t(status.st_size),         std::int64_t(status.st_mtim.tv_sec),
                      std::int64_t(status.st_mtim.tv_nsec), std::int64_t(status.st_ctim.tv_sec),
                      std::int64_t(status.st_ctim.tv_nsec)};
    return stamp;
}

// An imported mesh and every file its import read or looked for (the mesh, a material library, buffers,
// textures): the same while none of them changed.
struct CachedImport {
    ImportedMesh imported;
    std::vector<FileStamp> files;
};

std::size_t bytesOf(const ImportedMesh& imported) {
    const MeshData& mesh = imported.mesh;
    std::size_t bytes = mesh.positions.size() * (2 * sizeof(Eigen::Vector3f) + sizeof(Eigen::Vector2f)) +
                        mesh.indices.size() * sizeof(std::uint32_t);
    for (const ImportedMaterial& material : imported.materials)
        for (const auto* texture :
             {&material.baseColorTexture, &material.roughnessMetallicTexture, &material.normalTexture})
            bytes += *texture ? (*texture)->rgba.size() : 0;
    return bytes;
}

std::atomic<std::uint64_t> gFilesRead{0};

// Reads the mesh file at `path` (resolved and checked) with assimp, listing what it read in `reading`.
ImportedMesh readMeshFile(const std::string& path, const std::string& userPath, Reading& reading) {
    ++gFilesRead;
    Assimp::Importer importer;
    // Baking node transforms also joins meshes that share a material: one submesh per material group.
    // A file without normals gets smooth ones only across edges under 60 degrees, and hard edges at sharper
    // creases: a crate's faces are flat (smooth normals across a cube's edges shade it as a blob and make its
    // faces shadow themselves), a scanned or tessellated curved surface stays smooth, its vertices shared (so
    // that it still simplifies into levels of detail).
    importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 60.0f);
    const aiScene* scene =
        readWithAssimp(importer, path, userPath,
                       aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                           aiProcess_PreTransformVertices | aiProcess_FlipUVs | aiProcess_SortByPType,
                       reading.files, "importMesh");

    ImportedMesh out;
    out.mesh.name = std::filesystem::path(path).stem().string();
    // glTF is Y-up (its spec: +Y up, +Z forward, metres); spear is Z-up, as Unreal: a quarter turn about X,
    // (x, y, z) -> (x, -z, y), for positions and normals alike (a rotation: winding and handedness kept). The
    // other formats carry no axis convention and are read as they are (OBJ, PLY, STL: Z-up, as written).
    const bool yUp = isYUpFormat(path);
    auto axes = [yUp](const aiVector3D& v) {
        return yUp ? Eigen::Vector3f(v.x, -v.z, v.y) : Eigen::Vector3f(v.x, v.y, v.z);
    };
    reading.directory = std::filesystem::path(path).parent_path();
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue; // points and lines have no surface to render
        const auto base = static_cast<std::uint32_t>(out.mesh.positions.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            out.mesh.positions.push_back(axes(mesh->mVertices[v]));
            out.mesh.normals.push_back(axes(mesh->HasNormals() ? mesh->mNormals[v] : aiVector3D(0, 0, 1)));
            const aiVector3D uv =
                mesh->HasTextureCoords(0) ? mesh->mTextureCoords[0][v] : aiVector3D(0, 0, 0);
            out.mesh.uvs.push_back({uv.x, uv.y});
        }
        Submesh submesh{static_cast<std::uint32_t>(out.mesh.indices.size()), 0};
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3)
                continue;
            for (unsigned k = 0; k < 3; ++k)
                out.mesh.indices.push_back(base + face.mIndices[k]);
            submesh.indexCount += 3;
        }
        if (submesh.indexCount == 0)
            continue;
        out.mesh.submeshes.push_back(submesh);
        out.materials.push_back(mesh->mMaterialIndex < scene->mNumMaterials
                                    ? readMaterial(scene, scene->mMaterials[mesh->mMaterialIndex], reading)
                                    : ImportedMaterial{});
    }
    SP_CHECK(!out.mesh.submeshes.empty(), InvalidArgument, "importMesh(): '", path,
             "' contains no triangles");
    out.mesh.validate("importMesh");
    return out;
}

} // namespace

const aiScene* readWithAssimp(Assimp::Importer& importer, const std::string& path,
                              const std::string& userPath, unsigned flags,
                              std::vector<std::string>& filesRead, const char* function) {
    importer.SetIOHandler(new RegularFilesOnly(filesRead)); // the importer owns it
    base::Progress progress(std::string(function) + "(): " + std::filesystem::path(path).filename().string(),
                            1.0);
    importer.SetProgressHandler(new ReportProgress(progress)); // the importer owns it
    const aiScene* scene = importer.ReadFile(path, flags);
    importer.SetProgressHandler(nullptr); // the progress ends here; the handler must not outlive it
    SP_CHECK(scene != nullptr && !(scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE), InvalidArgument, function,
             "(): cannot read '", userPath, "': ", importer.GetErrorString());
    return scene;
}

ImportedMaterial importMaterial(const aiScene& scene, unsigned index, const std::filesystem::path& directory,
                                std::vector<std::string>& filesRead) {
    if (index >= scene.mNumMaterials)
        return {};
    Reading reading{directory, {}};
    ImportedMaterial out = readMaterial(&scene, scene.mMaterials[index], reading);
    filesRead.insert(filesRead.end(), reading.files.begin(), reading.files.end());
    return out;
}

bool isYUpFormat(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".gltf" || extension == ".glb";
}

std::uint64_t meshFilesRead() {
    return gFilesRead;
}

ImportedMesh importMesh(const std::string& userPath) {
    // Outside a server's file roots nothing is told about the file, not even whether it exists.
    const std::string path = resolveUserPath(findAsset(userPath), "importMesh()", "mesh file");
    SP_CHECK(std::filesystem::exists(path) && !std::filesystem::is_directory(path), NotFound,
             "importMesh(): no such file '", userPath, "'");
    checkRegularFile(path, "importMesh()", "mesh file"); // a FIFO or device: a clear error, not a hang
    // The physics' collision shape and each world's render scene import a file: read once while none of the
    // files its import read changed.
    static base::RecentCache<CachedImport> cache(kImportCacheBytes);
    if (const std::shared_ptr<const CachedImport> cached = cache.find(path))
        if (std::all_of(cached->files.begin(), cached->files.end(),
                        [](const FileStamp& file) { return stampOf(file.path) == file; }))
            return cached->imported;
    const FileStamp before = stampOf(path);
    Reading reading;
    ImportedMesh out = readMeshFile(path, userPath, reading);
    auto entry = std::make_shared<CachedImport>();
    entry->files.push_back(before);
    for (const std::string& file : reading.files)
        entry->files.push_back(stampOf(file));
    if (stampOf(path) == before) { // else it changed while read: not kept
        entry->imported = out;
        cache.insert(path, std::move(entry), bytesOf(out));
    }
    return out;
}

ImportedMeshIds addToScene(Scene& scene, const ImportedMesh& imported, bool shared) {
    ImportedMeshIds ids;
    const std::string key = shared ? contentKey(imported.mesh) : std::string();
    ids.mesh = scene.addMesh(imported.mesh, key);
    // A finely tessellated mesh gets coarser levels, drawn where it is small in the image (mesh_lods.h).
    // (Reported as progress: a mesh of a million triangles takes about a second.)
    std::vector<MeshLod> lods;
    const MeshData& full = scene.mesh(ids.mesh);
    const double expected = std::max(1.0, std::floor(std::log2(double(full.indices.size() / 3) / 512.0)));
    base::Progress progress("addToScene(): levels of detail of " + (full.name.empty() ? "a mesh" : full.name),
                            expected);
    // Shared meshes share their levels too (sharedLods(): made once per process).
    const std::shared_ptr<const MeshLevels> levels =
        key.empty() ? std::make_shared<const MeshLevels>(simplifiedLods(full, [&] { progress.advance(); }))
                    : sharedLods(key, full, [&] { progress.advance(); });
    for (const auto& [level, error] : *levels)
        lods.push_back(
            {scene.addMesh(level, key.empty() ? key : key + "@lod" + std::to_string(lods.size())), error});
    if (!lods.empty())
        scene.setMeshLods(ids.mesh, std::move(lods));
    ids.materials = addMaterialsToScene(scene, imported.materials, shared);
    return ids;
}

std::vector<MaterialId> addMaterialsToScene(Scene& scene, const std::vector<ImportedMaterial>& materials,
                                            bool shared) {
    std::vector<MaterialId> ids;
    auto texture = [&](const TextureImage& image, TextureEncoding encoding) {
        return scene.addTexture(image, encoding, shared ? contentKey(image, encoding) : std::string());
    };
    for (const ImportedMaterial& source : materials) {
        Material material = source.material;
        if (source.baseColorTexture)
            material.baseColorTexture = texture(*source.baseColorTexture, TextureEncoding::Srgb);
        if (source.roughnessMetallicTexture)
            material.roughnessMetallicTexture =
                texture(*source.roughnessMetallicTexture, TextureEncoding::Linear);
        if (source.normalTexture)
            material.normalTexture = texture(*source.normalTexture, TextureEncoding::Linear);
        ids.push_back(scene.addMaterial(material));
    }
    return ids;
}

} // namespace sp::render
