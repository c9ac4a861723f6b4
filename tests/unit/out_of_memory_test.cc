// An allocation that fails names what was being allocated (dem/core/out_of_memory.h; docs/input.md,
// "Memory"): under an address-space limit (ulimit -v, RLIMIT_AS) a little above what the process
// holds, the fill and the engine end in upgrain::Error naming them, not in a bare std::bad_alloc.
#include <gtest/gtest.h>
#include <mpi.h>
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>

#include "coupling/run/scene_run.h"
#include "dem/core/out_of_memory.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"

using namespace upgrain;

namespace {

// Whether the sanitizers' allocator runs this build: it reserves terabytes of shadow memory and
// aborts on a failed allocation instead of throwing std::bad_alloc.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// The process's address space now (VmSize of /proc/self/status), in bytes.
double address_space() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmSize:", 0) == 0) return 1024.0 * std::atof(line.c_str() + 7);
  return 0.0;
}

// ulimit -v at `room` bytes above what the process holds, for the scope; the soft limit only, so
// that it can be raised back.
class AddressSpaceLimit {
 public:
  explicit AddressSpaceLimit(double room) {
    ::getrlimit(RLIMIT_AS, &before_);
    rlimit l = before_;
    l.rlim_cur = static_cast<rlim_t>(address_space() + room);
    set_ = ::setrlimit(RLIMIT_AS, &l) == 0;
  }
  ~AddressSpaceLimit() { ::setrlimit(RLIMIT_AS, &before_); }
  AddressSpaceLimit(const AddressSpaceLimit&) = delete;
  AddressSpaceLimit& operator=(const AddressSpaceLimit&) = delete;
  [[nodiscard]] bool set() const { return set_; }

 private:
  rlimit before_{};
  bool set_ = false;
};

dem::SceneConfig scene_of(long count) {
  dem::SceneConfig s;
  s.particles.count = count;
  s.particles.radius = 1e-3;
  s.container.lx = s.container.ly = 0.2;
  s.time_step = 1e-6;
  return s;
}

}  // namespace

TEST(OutOfMemory, TheFillBeyondTheAddressSpaceLimitIsNamed) {
  if (kSanitized) GTEST_SKIP() << "the sanitizers' allocator aborts instead of throwing std::bad_alloc";
  const dem::SceneConfig s = scene_of(20'000'000);  // several GB of grains
  std::string message;
  {
    const AddressSpaceLimit limit(256e6);
    ASSERT_TRUE(limit.set());
    try {
      (void)coupling::fill_on_root(s, MPI_COMM_SELF);
    } catch (const Error& e) {
      message = e.what();
    }
  }
  std::printf("  %s\n", message.c_str());
  EXPECT_NE(message.find("out of memory while allocating the fill's grains (std::bad_alloc)"),
            std::string::npos)
      << message;
}

TEST(OutOfMemory, TheEngineBeyondTheAddressSpaceLimitIsNamed) {
  if (kSanitized) GTEST_SKIP() << "the sanitizers' allocator aborts instead of throwing std::bad_alloc";
  const dem::SceneConfig s = scene_of(400'000);
  dem::ParticleStore fill = dem::fill_container(s);
  std::string message;
  {
    // The store is moved in; the room is less than the lists, the cell order and the copies of a
    // rebuild take beside it.
    const AddressSpaceLimit limit(64e6);
    ASSERT_TRUE(limit.set());
    try {
      dem::Simulation sim(s, std::move(fill), MPI_COMM_SELF);
    } catch (const OutOfMemory& e) {
      message = e.what();
    }
  }
  std::printf("  %s\n", message.c_str());
  // The constructor's rebuild names itself; the constructor names the rest.
  EXPECT_NE(message.find("out of memory while allocating the "), std::string::npos) << message;
  EXPECT_NE(message.find("neighbour lists"), std::string::npos) << message;
}

// An inner allocation names itself more closely; the outer one does not replace it.
TEST(OutOfMemory, TheInnermostNameIsKept) {
  std::string message;
  try {
    allocating("the outer stage", [] { allocating("the inner array", [] { throw std::bad_alloc(); }); });
  } catch (const OutOfMemory& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("while allocating the inner array"), std::string::npos) << message;
}
