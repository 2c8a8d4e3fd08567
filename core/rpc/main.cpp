// spear-server: runs the engine as its own process and serves it over RPC.
//
//   spear-server --socket /tmp/spear.sock
//   spear-server --port 0 --token SECRET [--bind 127.0.0.1]
//   spear-server --socket /tmp/spear.sock --mode editor --scene assets/scenes/apartment.json
//   spear-server --socket /tmp/spear.sock --plugin build/plugin/python/my_plugin/libmy_plugin.so
//   SPEAR_PLUGIN_PATH=build/plugin/python spear-server --socket /tmp/spear.sock --plugin my_plugin
//
// Prints "spear-server: listening on <address>" once it accepts connections (clients that launch a
// server wait for that line), and exits cleanly on SIGTERM, SIGINT or a client's shutdown request.

#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <vector>

#include "core/base/error.h"
#include "core/plugin/plugin_loader.h"
#include "core/rpc/server.h"
#include "generated/engine/cpp/engine_types.gen.h"

namespace {
void usage() {
    std::fprintf(stderr, "usage: spear-server (--socket PATH | --port N --token TOKEN [--bind ADDRESS])\n"
                         "                    [--mode game|editor] [--scene FILE] [--fixed-delta-seconds S]\n"
                         "                    [--plugin LIBRARY|NAME]... [--exit-with-parent]\n");
}
} // namespace

int main(int argc, char** argv) {
    sp::rpc::ServerOptions options;
    sp::world::Engine::Settings settings;
    std::vector<std::string> plugins;
    if (const char* token = std::getenv("SPEAR_TOKEN"))
        options.token = token;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool hasValue = i + 1 < argc;
        if (arg == "--socket" && hasValue)
            options.socketPath = argv[++i];
        else if (arg == "--port" && hasValue)
            options.tcpPort = std::atoi(argv[++i]);
        else if (arg == "--bind" && hasValue)
            options.bindAddress = argv[++i];
        else if (arg == "--token" && hasValue)
            options.token = argv[++i];
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
        else if (arg == "--exit-with-parent") {
            // A server launched by a client goes away with it, even if the client is killed.
            const pid_t parent = ::getppid();
            ::prctl(PR_SET_PDEATHSIG, SIGTERM);
            if (::getppid() != parent)
                return 0;
        } else {
            usage();
            return 2;
        }
    }
    if (options.socketPath.empty() && options.tcpPort < 0) {
        usage();
        return 2;
    }
    try {
        // Before the engine: its scene may name the plugins' classes.
        for (const std::string& path : plugins)
            sp::plugin::load(path);
        sp::world::Engine engine(settings);
        sp::rpc::Server server(engine, options, spear_register_engine_types_api_hash());
        std::signal(SIGTERM, [](int) { sp::rpc::Server::stop(); });
        std::signal(SIGINT, [](int) { sp::rpc::Server::stop(); });
        std::signal(SIGPIPE, SIG_IGN);
        std::printf("spear-server: listening on %s\n", server.address().c_str());
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
