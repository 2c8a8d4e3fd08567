#include "core/base/recycled_blocks.h"

#include <deque>
#include <mutex>
#include <utility>
#include <vector>

namespace sp {

namespace {
struct BlockPool {
    std::mutex mutex;
    std::deque<std::pair<std::size_t, char*>> kept; // oldest first
    std::size_t keptBytes = 0;
};

// Never destroyed: an array (a numpy array's storage, say) may be let go after static destructors ran.
BlockPool& blockPool() {
    static BlockPool* instance = new BlockPool;
    return *instance;
}

void giveBack(char* block, std::size_t bytes) {
    if (bytes > kMaxRecycledBytes) {
        delete[] block;
        return;
    }
    std::vector<char*> released;
    {
        BlockPool& p = blockPool();
        std::lock_guard lock(p.mutex);
        p.kept.emplace_back(bytes, block);
        p.keptBytes += bytes;
        while (p.keptBytes > kMaxRecycledBytes) {
            released.push_back(p.kept.front().second);
            p.keptBytes -= p.kept.front().first;
            p.kept.pop_front();
        }
    }
    for (char* old : released) // outside the lock: freeing a large block is a system call
        delete[] old;
}
} // namespace

std::shared_ptr<char[]> takeRecycledBlock(std::size_t bytes) {
    char* block = nullptr;
    {
        BlockPool& p = blockPool();
        std::lock_guard lock(p.mutex);
        // From the newest: its pages are the likeliest to be in the caches still.
        for (auto it = p.kept.rbegin(); it != p.kept.rend(); ++it)
            if (it->first == bytes) {
                block = it->second;
                p.keptBytes -= bytes;
                p.kept.erase(std::next(it).base());
                break;
            }
    }
    if (!block)
        block = new char[bytes];
    return std::shared_ptr<char[]>(block, [bytes](char* owned) { giveBack(owned, bytes); });
}

std::size_t recycledBytesKept() {
    BlockPool& p = blockPool();
    std::lock_guard lock(p.mutex);
    return p.keptBytes;
}

} // namespace sp
