// spear_rpc_fuzz: a deterministic mutation fuzzer for the RPC message decoder and dispatcher, in one
// process with a real engine (no sockets: sp::rpc::Dispatcher is what a server runs for each message).
//
//   spear_rpc_fuzz CORPUS_DIR [--runs N] [--seed S] [--report-every N] [--stats]
//
// The corpus holds request bodies captured from a client session (capture_corpus.py). They are replayed
// once in order (so that the handles they name exist), then each run takes one, applies one to four
// mutations (bit flips, interesting bytes and integers, inserted, deleted and repeated ranges, splices
// with another seed, truncation) and hands it to the dispatcher: on the greeted session, or 1 run in 16
// on a fresh session that has not said hello. What must hold for every input:
//   - handle() does not throw, crash, hang or abort (the sanitizer builds catch memory errors);
//   - the reply is one msgpack map with an "id" and either "ok" or "error" (a batch: an array of them);
//   - the engine keeps serving: an echo on a fresh session succeeds after every 1000 runs.
// A failing input is written to fuzz-failure-<run>.msgpack and the process exits 1. One engine serves every
// run (a new one would give its world another handle, and the seeds' handles would all be stale); every
// 10000 runs the actors the inputs spawned are destroyed.

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/base/regular_file.h"
#include "core/rpc/dispatcher.h"
#include "core/world/actor.h"
#include "core/world/world.h"
#include "generated/engine/cpp/engine_types.gen.h"

namespace {

using Bytes = std::string;

std::vector<Bytes> readCorpus(const std::filesystem::path& directory) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory))
        if (entry.path().extension() == ".msgpack")
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::vector<Bytes> corpus;
    for (const auto& file : files) {
        std::ifstream in(file, std::ios::binary);
        corpus.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    return corpus;
}

class Mutator {
  public:
    explicit Mutator(std::uint64_t seed) : random_(seed) {}

    std::size_t below(std::size_t n) {
        return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(random_);
    }

    Bytes mutate(Bytes input, const std::vector<Bytes>& corpus) {
        // Half the inputs carry one mutation, so that many still decode and reach the engine's functions.
        const std::size_t count = below(2) ? 1 : 1 + below(4);
        for (std::size_t i = 0; i < count; ++i)
            mutateOnce(input, corpus);
        return input;
    }

  private:
    void mutateOnce(Bytes& b, const std::vector<Bytes>& corpus) {
        // msgpack type bytes and boundary values: nil, bools, the int/str/bin/array/map/ext headers.
        static const unsigned char kInteresting[] = {0x00, 0x01, 0x7f, 0x80, 0xc0, 0xc2, 0xc3, 0xc4, 0xc7,
                                                     0xcc, 0xcd, 0xce, 0xcf, 0xd0, 0xd3, 0xd4, 0xd9, 0xdb,
                                                     0xdc, 0xdd, 0xde, 0xdf, 0xe0, 0xff, 0x90, 0x9f, 0xa0};
        static const std::uint64_t kIntegers[] = {0,
                                                  1,
                                                  0x7f,
                                                  0xff,
                                                  0x7fff,
                                                  0xffff,
                                                  0x7fffffff,
                                                  0xffffffff,
                                                  0x8000000000000000ull,
                                                  0xffffffffffffffffull,
                                                  16384,
                                                  16385};
        switch (below(b.empty() ? 1 : 9)) {
        case 0: // insert random bytes
            b.insert(below(b.size() + 1), randomBytes(1 + below(8)));
            break;
        case 1:
            b[below(b.size())] ^= char(1u << below(8));
            break;
        case 2:
            b[below(b.size())] = char(kInteresting[below(sizeof kInteresting)]);
            break;
        case 3: { // an interesting integer, big endian as msgpack writes them
            const std::uint64_t value = kIntegers[below(std::size(kIntegers))];
            const std::size_t width = std::size_t(1) << below(4);
            const std::size_t at = below(b.size());
            for (std::size_t k = 0; k < width && at + k < b.size(); ++k)
                b[at + k] = char(value >> (8 * (width - 1 - k)));
            break;
        }
        case 4: { // delete a range
            const std::size_t at = below(b.size());
            b.erase(at, 1 + below(std::min<std::size_t>(16, b.size() - at)));
            break;
        }
        case 5: { // repeat a range
            const std::size_t at = below(b.size());
            const std::size_t length = 1 + below(std::min<std::size_t>(32, b.size() - at));
            b.insert(at, b.substr(at, length));
            break;
        }
        case 6: { // splice: a prefix of this one, the rest of another
            const Bytes& other = corpus[below(corpus.size())];
            b = b.substr(0, below(b.size() + 1)) + other.substr(below(other.size() + 1));
            break;
        }
        case 7:
            b.resize(below(b.size() + 1));
            break;
        default: { // copy a range of another seed over this one
            const Bytes& other = corpus[below(corpus.size())];
            if (other.empty())
                break;
            const std::size_t from = below(other.size());
            const std::size_t length = 1 + below(std::min<std::size_t>(32, other.size() - from));
            const std::size_t at = below(b.size());
            b.replace(at, std::min(length, b.size() - at), other.substr(from, length));
        }
        }
    }

    Bytes randomBytes(std::size_t n) {
        Bytes out(n, '\0');
        for (char& c : out)
            c = char(below(256));
        return out;
    }

    std::mt19937_64 random_;
};

// True when `reply` is one well-formed reply map ({"id", "ok" | "error"}).
bool wellFormedMap(const msgpack::object& map) {
    if (map.type != msgpack::type::MAP)
        return false;
    bool id = false, outcome = false;
    for (std::uint32_t i = 0; i < map.via.map.size; ++i) {
        const msgpack::object& key = map.via.map.ptr[i].key;
        if (key.type != msgpack::type::STR)
            return false;
        const std::string name(key.via.str.ptr, key.via.str.size);
        id = id || name == "id";
        outcome = outcome || name == "ok" || name == "error";
    }
    return id && outcome;
}

bool wellFormed(const msgpack::sbuffer& reply) {
    try {
        const msgpack::object_handle handle = msgpack::unpack(reply.data(), reply.size());
        const msgpack::object& value = handle.get();
        if (value.type == msgpack::type::ARRAY) { // a batch
            for (std::uint32_t i = 0; i < value.via.array.size; ++i)
                if (!wellFormedMap(value.via.array.ptr[i]))
                    return false;
            return true;
        }
        return wellFormedMap(value);
    } catch (const std::exception&) {
        return false;
    }
}

// Error replies by the start of their message, to see how deep the inputs reach (--stats).
std::map<std::string, std::uint64_t> gErrorKinds;
std::uint64_t gOkReplies = 0;

void countOutcome(const msgpack::sbuffer& reply) {
    const std::string text(reply.data(), reply.size());
    const std::size_t error = text.find("error");
    if (error == std::string::npos) {
        ++gOkReplies;
        return;
    }
    // The message follows the error class: keep its first words, without the values in it.
    std::string kind = text.substr(error + 5, 60);
    for (char& c : kind)
        if (c < 32 || c > 126 || std::isdigit(static_cast<unsigned char>(c)))
            c = '.';
    ++gErrorKinds[kind];
}

// One engine and dispatcher for every run, after the corpus has been replayed on the greeted session.
struct Harness {
    sp::engine::Engine engine;
    sp::rpc::Dispatcher dispatcher{engine, spear_register_engine_types_api_hash(), ""};
    sp::rpc::Session session;
    std::vector<AActor*> seedActors;

    explicit Harness(const std::vector<Bytes>& corpus) {
        for (const Bytes& seed : corpus)
            run(seed, session);
        seedActors = engine.GetGameWorld().find_actors();
    }

    // Destroys the actors the inputs spawned (the seeds' own stay, so that their handles keep working):
    // thousands of them would make every tick slower and the fuzzer with it.
    void destroySpawned() {
        UWorld& world = engine.GetGameWorld();
        for (AActor* actor : world.find_actors())
            if (std::find(seedActors.begin(), seedActors.end(), actor) == seedActors.end())
                world.destroy_actor(actor);
    }
    // Empty when fine, else what broke.
    std::string run(const Bytes& input, sp::rpc::Session& on) {
        msgpack::sbuffer reply;
        try {
            dispatcher.handle(input.data(), input.size(), on, reply, nullptr);
        } catch (const std::exception& error) {
            return std::string("handle() threw: ") + error.what();
        }
        if (!wellFormed(reply))
            return "the reply is not a well-formed reply map";
        countOutcome(reply);
        return "";
    }
};

void writeFailure(std::uint64_t run, const Bytes& input, const std::string& what) {
    const std::string name = "fuzz-failure-" + std::to_string(run) + ".msgpack";
    std::ofstream(name, std::ios::binary).write(input.data(), std::streamsize(input.size()));
    std::fprintf(stderr, "spear_rpc_fuzz: run %llu: %s (input written to %s)\n", (unsigned long long)run,
                 what.c_str(), name.c_str());
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: spear_rpc_fuzz CORPUS_DIR [--runs N] [--seed S] [--report-every N]\n");
        return 2;
    }
    std::uint64_t runs = 100000, seed = 1, reportEvery = 0;
    bool stats = false;
    for (int i = 2; i < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--stats") {
            stats = true;
            --i;
            continue;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "spear_rpc_fuzz: option '%s' needs a value\n", flag.c_str());
            return 2;
        }
        const std::uint64_t value = std::strtoull(argv[i + 1], nullptr, 10);
        if (flag == "--runs")
            runs = value;
        else if (flag == "--seed")
            seed = value;
        else if (flag == "--report-every")
            reportEvery = value;
        else {
            std::fprintf(stderr, "spear_rpc_fuzz: unknown option '%s'\n", flag.c_str());
            return 2;
        }
    }
    std::vector<Bytes> corpus = readCorpus(argv[1]);
    if (corpus.empty()) {
        std::fprintf(stderr, "spear_rpc_fuzz: no .msgpack seeds in '%s'\n", argv[1]);
        return 2;
    }
    // The captured hello carries the API hash of the build that captured it, and every new reflected member
    // changes the hash: the first seed is made anew with this build's, so that the replay gets past hello.
    corpus.front() = [] {
        msgpack::sbuffer out;
        msgpack::packer<msgpack::sbuffer> packer(&out);
        packer.pack_map(4);
        packer.pack(std::string("id")), packer.pack(1);
        packer.pack(std::string("op")), packer.pack(std::string("hello"));
        packer.pack(std::string("api_hash")),
            packer.pack(std::string(spear_register_engine_types_api_hash()));
        packer.pack(std::string("token")), packer.pack(std::string());
        return Bytes(out.data(), out.size());
    }();
    // Inputs may name files (save_scene of a mutated path): they can only touch a scratch folder.
    const std::filesystem::path scratch =
        std::filesystem::temp_directory_path() / ("spear_rpc_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(scratch);
    std::filesystem::current_path(scratch);
    sp::confineUserFiles({scratch.string()});

    Harness harness(corpus);
    // After the replay no scene file can be loaded again: a load replaces every actor, and the handles the
    // seeds name would all be stale from then on. Save and load still run, into a refusal.
    std::filesystem::create_directories(scratch / "empty");
    sp::confineUserFiles({(scratch / "empty").string()});
    const Bytes echo = [] {
        msgpack::sbuffer out;
        msgpack::packer<msgpack::sbuffer> packer(&out);
        packer.pack_map(3);
        packer.pack(std::string("id")), packer.pack(1);
        packer.pack(std::string("op")), packer.pack(std::string("echo"));
        packer.pack(std::string("value")), packer.pack(42);
        return Bytes(out.data(), out.size());
    }();
    Mutator mutator(seed);
    std::uint64_t freshSessions = 0;
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t run = 1; run <= runs; ++run) {
        const Bytes input = mutator.mutate(corpus[mutator.below(corpus.size())], corpus);
        sp::rpc::Session fresh;
        const bool greeted = mutator.below(16) != 0 && !harness.session.closeAfterReply;
        sp::rpc::Session& session = greeted ? harness.session : fresh;
        freshSessions += greeted ? 0 : 1;
        if (const std::string broke = harness.run(input, session); !broke.empty()) {
            writeFailure(run, input, broke);
            return 1;
        }
        if (!greeted)
            harness.dispatcher.endSession(fresh);
        if (harness.session.closeAfterReply || harness.session.shutdownRequested) {
            harness.dispatcher.endSession(harness.session);
            harness.session = {};
            harness.run(corpus.front(), harness.session); // hello again
        }
        if (run % 1000 == 0) { // still serving: a fresh client's echo works
            sp::rpc::Session probe;
            harness.run(corpus.front(), probe);
            msgpack::sbuffer reply;
            harness.dispatcher.handle(echo.data(), echo.size(), probe, reply, nullptr);
            const std::string text(reply.data(), reply.size());
            if (text.find("ok") == std::string::npos) {
                writeFailure(run, input, "the engine stopped serving (echo failed after this input)");
                return 1;
            }
            harness.dispatcher.endSession(probe);
        }
        if (run % 10000 == 0)
            harness.destroySpawned();
        if (reportEvery && run % reportEvery == 0) {
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::printf("spear_rpc_fuzz: %llu runs, %.0f/s\n", (unsigned long long)run,
                        double(run) / seconds);
            std::fflush(stdout);
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
        "spear_rpc_fuzz: %llu runs (%llu on fresh sessions) from %zu seeds in %.1f s (%.0f/s), seed %llu: "
        "no failure\n",
        (unsigned long long)runs, (unsigned long long)freshSessions, corpus.size(), seconds,
        double(runs) / seconds, (unsigned long long)seed);
    if (stats) {
        std::printf("  ok replies: %llu\n", (unsigned long long)gOkReplies);
        std::vector<std::pair<std::uint64_t, std::string>> kinds;
        for (const auto& [kind, count] : gErrorKinds)
            kinds.emplace_back(count, kind);
        std::sort(kinds.rbegin(), kinds.rend());
        for (std::size_t i = 0; i < kinds.size() && i < 40; ++i)
            std::printf("  %8llu  %s\n", (unsigned long long)kinds[i].first, kinds[i].second.c_str());
        std::printf("  (%zu kinds of error)\n", kinds.size());
    }
    std::filesystem::current_path("/");
    std::filesystem::remove_all(scratch);
    return 0;
}
