#pragma once
// Where assets named by a relative path are found, so that the built-in assets (the default scene, the
// blueprints) load the same from a source checkout, an installed package or any working directory.
//
// A relative path (`assets/scenes/apartment.json`) is looked up in the working directory first (a user's
// own file), then in each folder of SPEAR_ASSET_PATH (colon-separated), then in the host's built-in
// folder: the folder that holds spear's `assets/` (the checkout, or the installed package). UE's
// `/Game/...` names are `assets/...` ("/Game/scenes/apartment" is assets/scenes/apartment.json; a name
// without an extension gets `.json`). An absolute path is itself. A scene file's streaming levels and mesh
// files named relative to it are looked for in its folder first (UStaticMeshComponent::SceneFolderScope).

#include <string>
#include <string_view>
#include <vector>

namespace sp {

// The host's folder that holds `assets/`: set once by the engine module (from the Python package's
// location) or by spear-server (from its executable's location).
void setBuiltinAssetFolder(std::string folder);

// Sets the built-in folder to `packageFolder` when it holds `assets/` (an installed package), else to the
// checkout this engine was built from (a source tree, where the package folder has no assets of its own).
// Returns the folder chosen.
std::string useBuiltinAssetsOf(const std::string& packageFolder);

// The folders searched for a relative name after the working directory, in order: SPEAR_ASSET_PATH's,
// then the built-in one.
std::vector<std::string> assetSearchPath();

// The path to open for an asset named `name`: the first existing candidate, or `name` unchanged when none
// exists (so that the reader's own "no such file" names what the user wrote).
std::string findAsset(std::string_view name);

} // namespace sp
