// tests/test_support.cpp: subprocess running, temp folders, shared data lookup.
#include "test_support.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <new>
#include <random>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

std::atomic<size_t> largest{0};

} // namespace

// The replaceable global allocation functions, recording the largest request. Every form that
// the library may pair with another is replaced here, so that a block always goes back to the
// allocator it came from (std::stable_partition's buffer comes from the nothrow form and returns
// through the plain delete; the sanitizer's own nothrow form would be freed by std::free). The
// aligned and array forms forward to these.
namespace {

void* recordedAllocation(size_t bytes) noexcept
{
    size_t seen = largest.load(std::memory_order_relaxed);
    while (bytes > seen && !largest.compare_exchange_weak(seen, bytes, std::memory_order_relaxed)) {
    }
    return std::malloc(bytes ? bytes : 1);
}

} // namespace

void* operator new(size_t bytes)
{
    if (void* p = recordedAllocation(bytes))
        return p;
    throw std::bad_alloc();
}

void* operator new(size_t bytes, const std::nothrow_t&) noexcept
{
    return recordedAllocation(bytes);
}

void* operator new[](size_t bytes)
{
    return operator new(bytes);
}

void* operator new[](size_t bytes, const std::nothrow_t&) noexcept
{
    return recordedAllocation(bytes);
}

void operator delete(void* p) noexcept
{
    std::free(p);
}

void operator delete(void* p, size_t) noexcept
{
    std::free(p);
}

void operator delete(void* p, const std::nothrow_t&) noexcept
{
    std::free(p);
}

void operator delete[](void* p) noexcept
{
    std::free(p);
}

void operator delete[](void* p, size_t) noexcept
{
    std::free(p);
}

void operator delete[](void* p, const std::nothrow_t&) noexcept
{
    std::free(p);
}

namespace wisp::test {

void resetLargestAllocation()
{
    largest.store(0);
}

size_t largestAllocation()
{
    return largest.load();
}

vk::ContextOptions validatedOptions()
{
    // WISP_TEST_SYNC_VALIDATION=1 (scripts/test.sh --ci runs the GPU suites once so) adds the
    // layer's synchronization checks: any hazard is a validation message and fails the test.
    const char* sync = std::getenv("WISP_TEST_SYNC_VALIDATION");
    return {.validation = true, .synchronizationValidation = sync != nullptr && std::string(sync) == "1"};
}

RunResult runWisp(const std::string& args, const std::string& envPrefix)
{
    TempDir dir;
    std::string command = envPrefix + " '" WISP_BINARY "' " + args + " >'" + (dir / "out").string() + "' 2>'" +
                          (dir / "err").string() + "' </dev/null";
    int raw = std::system(command.c_str());
    RunResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
    r.out = readFile(dir / "out");
    r.err = readFile(dir / "err");
    return r;
}

TempDir::TempDir()
{
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("wisp-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir()
{
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

SmallDisk::SmallDisk(size_t bytes)
{
    std::string options = "size=" + std::to_string(bytes);
    if (::mount("tmpfs", dir_.path().c_str(), "tmpfs", MS_NOSUID | MS_NODEV, options.c_str()) == 0)
        mounted_ = true;
    else
        whyNot_ = std::string("mount: ") + std::strerror(errno);
}

SmallDisk::~SmallDisk()
{
    if (mounted_)
        ::umount2(dir_.path().c_str(), MNT_DETACH);
}

size_t SmallDisk::fill() const
{
    int fd = ::open((dir_ / "filler").c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0)
        return 0;
    std::string block(512, 'x');
    size_t held = 0;
    for (;;) {
        ssize_t n = ::write(fd, block.data(), block.size());
        if (n <= 0)
            break;
        held += size_t(n);
    }
    ::close(fd);
    return held;
}

void writeFile(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string readFile(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path sharedData(const std::string& relative)
{
    std::filesystem::path p = std::filesystem::path(WISP_SHARED_DATA) / relative;
    std::error_code ec;
    return std::filesystem::exists(p, ec) ? p : std::filesystem::path();
}

} // namespace wisp::test
