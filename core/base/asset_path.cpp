#include "core/base/asset_path.h"

#include <cstdlib>
#include <filesystem>
#include <mutex>

namespace sp {

namespace {
std::mutex gMutex;
std::string gBuiltin;

bool isFile(const std::filesystem::path& path) {
    std::error_code error;
    return std::filesystem::exists(path, error) && !std::filesystem::is_directory(path, error);
}
} // namespace

void setBuiltinAssetFolder(std::string folder) {
    std::lock_guard lock(gMutex);
    gBuiltin = std::move(folder);
}

std::string useBuiltinAssetsOf(const std::string& packageFolder) {
    std::error_code error;
    const bool installed =
        std::filesystem::is_directory(std::filesystem::path(packageFolder) / "assets", error);
    std::string folder = installed ? packageFolder : std::string(SPEAR_SOURCE_FOLDER);
    setBuiltinAssetFolder(folder);
    return folder;
}

std::vector<std::string> assetSearchPath() {
    std::vector<std::string> folders;
    if (const char* variable = std::getenv("SPEAR_ASSET_PATH")) {
        std::string_view rest(variable);
        while (!rest.empty()) {
            const size_t colon = rest.find(':');
            if (std::string_view folder = rest.substr(0, colon); !folder.empty())
                folders.emplace_back(folder);
            rest = colon == std::string_view::npos ? std::string_view() : rest.substr(colon + 1);
        }
    }
    std::lock_guard lock(gMutex);
    if (!gBuiltin.empty())
        folders.push_back(gBuiltin);
    return folders;
}

std::string findAsset(std::string_view name) {
    std::string relative(name);
    if (name.starts_with("/Game/")) {
        relative = "assets/" + std::string(name.substr(6));
        if (std::filesystem::path(relative).extension().empty())
            relative += ".json";
    }
    if (relative.empty() || std::filesystem::path(relative).is_absolute() || isFile(relative))
        return relative;
    for (const std::string& folder : assetSearchPath())
        if (const std::filesystem::path candidate = std::filesystem::path(folder) / relative;
            isFile(candidate))
            return candidate.string();
    return relative;
}

} // namespace sp
