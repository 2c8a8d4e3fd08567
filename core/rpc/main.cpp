// spear-server: runs the engine as its own process and serves it over RPC.
//
//   spear-server --socket /tmp/spear.sock
//   spear-server --port 0 --token-file ~/.spear-token [--bind 127.0.0.1]   (or SPEAR_TOKEN=... in the
//                                                                           environment; --token SECRET
//                                                                           works too, but any local user
//                                                                           can read a command line)
//   spear-server --socket /tmp/spear.sock --mode editor --scene assets/scenes/apartment.json
//   spear-server --socket /tmp/spear.sock --inspect 8080    (and a browser on the address it prints)
//   spear-server --socket /tmp/spear.sock --plugin build/plugin/python/my_plugin/libmy_plugin.so
//   SPEAR_PLUGIN_PATH=build/plugin/python spear-server --socket /tmp/spear.sock --plugin my_plugin
//
// Over RPC, load_plugin loads only the plugins named by --plugin or found in the server's SPEAR_PLUGIN_PATH;
// --allow-remote-plugin-load lets clients load any library (spear.Instance(server="launch") passes it: that
// server is private to the user who started it).
//
// Files that clients name (scenes, blueprints, meshes, textures, save_scene targets) must lie in a
// --file-root folder (repeatable; default: the server's working directory; relative paths are relative to the
// first) or among the built-in assets and SPEAR_ASSET_PATH's folders, which clients read but never write
// (save_scene, render jobs): a client otherwise reads and writes whatever the server's user can.
// --file-root / allows any path, assets included (launch passes it, for the same reason as
// --allow-remote-plugin-load). The server's own --scene and --plugin are not confined.
//
// SPEAR_RPC_SPIN_US (microseconds, default 100) is how long the server polls its sockets before it sleeps
// (spin_poll.h); a client that launches the server passes its own setting on through the environment.
//
// --inspect PORT serves the inspector (a page in the browser over the same protocol; server.h) on loopback,
// guarded by the TCP token or, on a Unix socket, by a token made for it; the page is in --inspect-root
// (default: the inspector folder of the package, beside bin/). It prints "spear-server: inspector on
// http://...?token=...".
//
// Prints "spear-server: listening on <address>" once it accepts connections (clients that launch a
// server wait for that line), and exits cleanly on SIGTERM, SIGINT or a client's shutdown request.

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/base/process_memory.h"
#include "core/base/regular_file.h"
#include "core/plugin/plugin_loader.h"
#include "core/rpc/server.h"
#include "core/rpc/spin_poll.h"
#include "generated/engine/cpp/engine_types.gen.h"

namespace {
// To stdout for --help (asked for: exit 0), to stderr for a command line it cannot run (exit 2).
void usage(std::FILE* to = stderr) {
    std::fprintf(
        to,
        "usage: spear-server (--socket PATH | --port N (--token-file FILE | --token TOKEN) [--bind "
        "ADDRESS])\n"
        "                    [--mode game|editor] [--scene FILE] [--fixed-delta-seconds S]\n"
        "                    [--plugin LIBRARY|NAME]... [--allow-remote-plugin-load] [--file-root DIR]...\n"
        "                    [--inspect PORT [--inspect-root DIR]] [--exit-with-parent]\n"
        "  The TCP token may also come from the SPEAR_TOKEN environment variable.\n");
}

// The token in `path`, without the line break an editor adds. The file must be the user's own and
// owner-only, as an ssh key must: a token others can read protects nothing.
std::string readTokenFile(const std::string& path) {
    struct stat info {};
    SP_CHECK(::stat(path.c_str(), &info) == 0, sp::NotFound, "spear-server: --token-file '", path,
             "': ", std::strerror(errno));
    SP_CHECK(S_ISREG(info.st_mode), sp::InvalidArgument, "spear-server: --token-file '", path,
             "' is not a regular file");
    SP_CHECK(info.st_uid == ::getuid() && (info.st_mode & 077) == 0, sp::InvalidArgument,
             "spear-server: --token-file '", path,
             "' must belong to this user and be readable by it alone (mode ", std::oct, (info.st_mode & 0777),
             std::dec, "); run chmod 600 '", path, "'");
    std::ifstream file(path);
    std::stringstream text;
    text << file.rdbuf();
    std::string token = text.str();
    while (!token.empty() && (token.back() == '\n' || token.back() == '\r'))
        token.pop_back();
    SP_CHECK(!token.empty(), sp::InvalidArgument, "spear-server: --token-file '", path, "' is empty");
    return token;
}

// A server launched by a client goes away with it, even if the client is killed: stopped (SIGTERM) once its
// parent process is gone (it is no longer our parent). Polled, not PR_SET_PDEATHSIG, which fires when the
// launching *thread* exits: a client that starts servers from worker threads would lose them with the
// threads.
void watchParent(pid_t parent) {
    std::thread([parent] {
        while (::getppid() == parent)
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        ::kill(::getpid(), SIGTERM);
    }).detach();
}

} // namespace

int main(int argc, char** argv) {
    // The server's process is ours to tune (core/base/process_memory.h).
    sp::keepFreedMemory();
    sp::rpc::ServerOptions options;
    sp::engine::Engine::Settings settings;
    std::vector<std::string> plugins;
    std::vector<std::string> fileRoots;
    std::string tokenFile;
    pid_t exitWithParent = 0;
    if (const char* token = std::getenv("SPEAR_TOKEN"))
        options.token = token;
    // The options that take a value: one given last without it is named, not taken for an unknown option.
    static const std::set<std::string> kValued{
        "--socket", "--port",  "--bind",   "--token",     "--token-file", "--fixed-delta-seconds",
        "--mode",   "--scene", "--plugin", "--file-root", "--inspect",    "--inspect-root"};
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool hasValue = i + 1 < argc;
        if (arg == "--help" || arg == "-h") {
            usage(stdout);
            return 0;
        }
        if (kValued.contains(arg) && !hasValue) {
            std::fprintf(stderr, "spear-server: %s needs a value\n", arg.c_str());
            usage();
            return 2;
        }
        if (arg == "--socket" && hasValue)
            options.socketPath = argv[++i];
        else if (arg == "--port" && hasValue)
            options.tcpPort = std::atoi(argv[++i]);
        else if (arg == "--bind" && hasValue)
            options.bindAddress = argv[++i];
        else if (arg == "--token" && hasValue)
            options.token = argv[++i];
        else if (arg == "--token-file" && hasValue)
            tokenFile = argv[++i];
        else if (arg == "--allow-remote-plugin-load")
            options.allowRemotePluginLoad = true;
        else if (arg == "--fixed-delta-seconds" && hasValue)
            settings.fixedDeltaSeconds = std::atof(argv[++i]);
        else if (arg == "--mode" && hasValue) {
            const std::string mode = argv[++i];
            if (mode != "game" && mode != "editor") {
                std::fprintf(stderr, "spear-server: --mode must be 'game' or 'editor', got '%s'\n",
                             mode.c_str());
                return 2;
            }
            settings.editor = mode == "editor";
        } else if (arg == "--scene" && hasValue)
            settings.scene = argv[++i];
        else if (arg == "--plugin" && hasValue)
            plugins.push_back(argv[++i]);
        else if (arg == "--file-root" && hasValue)
            fileRoots.push_back(argv[++i]);
        else if (arg == "--inspect" && hasValue)
            options.inspectPort = std::atoi(argv[++i]);
        else if (arg == "--inspect-root" && hasValue)
            options.inspectRoot = argv[++i];
        else if (arg == "--exit-with-parent") {
            // The launcher's pid when it says it (a launcher gone before this line ran left us to init or
            // a subreaper, whose pid getppid() would return), else the parent's now.
            const char* launcher = std::getenv("SPEAR_PARENT_PID");
            exitWithParent = launcher ? pid_t(std::atol(launcher)) : ::getppid();
        } else {
            std::fprintf(stderr, "spear-server: unknown option '%s'\n", arg.c_str());
            usage();
            return 2;
        }
    }
    if (options.socketPath.empty() && options.tcpPort < 0) {
        std::fprintf(stderr, "spear-server: say where to listen: --socket PATH or --port N\n");
        usage();
        return 2;
    }
    try {
        if (!tokenFile.empty())
            options.token = readTokenFile(tokenFile);
        options.plugins = plugins;
        options.spin = sp::rpc::spinFromEnvironment();
        // Before the engine: its scene may name the plugins' classes.
        for (const std::string& path : plugins)
            sp::plugin::load(path);
        // Built-in assets: beside an installed package (spear/bin/spear-server, spear/assets), else the
        // checkout the server was built from. Before the engine, whose --scene may be one.
        const std::filesystem::path package =
            std::filesystem::read_symlink("/proc/self/exe").parent_path().parent_path();
        const std::string builtin = sp::useBuiltinAssetsOf(package);
        if (options.inspectRoot.empty()) // also for a client's inspect request
            options.inspectRoot = (package / "inspector").string();
        sp::engine::Engine engine(settings);
        // After the engine has read the server's own --scene: from here on, paths come from clients. They
        // may read the built-in assets and the asset folders the server's user named (SPEAR_ASSET_PATH).
        // They may write only under the file roots, and never into those asset folders.
        if (fileRoots.empty())
            fileRoots.push_back(std::filesystem::current_path().string());
        std::vector<std::string> assetFolders;
        for (const std::string& folder : sp::assetSearchPath())
            if (std::filesystem::is_directory(folder))
                assetFolders.push_back(folder == builtin ? folder + "/assets" : folder);
        // --file-root / confines nothing (a launched server's client is its user, as in-process): there the
        // asset folders stay writable as they are in-process.
        const bool unconfined = std::any_of(fileRoots.begin(), fileRoots.end(), [](const std::string& root) {
            return std::filesystem::weakly_canonical(root) == "/";
        });
        if (unconfined)
            fileRoots.insert(fileRoots.end(), assetFolders.begin(), assetFolders.end());
        sp::confineUserFiles(fileRoots, unconfined ? std::vector<std::string>{} : assetFolders);
        sp::rpc::Server server(engine, options, spear_register_engine_types_api_hash());
        std::signal(SIGTERM, [](int) { sp::rpc::Server::stop(); });
        std::signal(SIGINT, [](int) { sp::rpc::Server::stop(); });
        std::signal(SIGPIPE, SIG_IGN);
        if (exitWithParent > 0)
            watchParent(exitWithParent);
        std::printf("spear-server: listening on %s\n", server.address().c_str());
        if (!server.inspectUrl().empty())
            std::printf("spear-server: inspector on %s\n", server.inspectUrl().c_str());
        std::fflush(stdout);
        server.run();
    } catch (const std::exception& e) {
        // "<spear.errors class>: message", so that a client that launched this server raises the same
        // error the in-process engine would.
        std::fprintf(stderr, "%s: %s\n", sp::pythonErrorClass(e), e.what());
        return 1;
    }
    return 0;
}
