#include "ui/mapped_splat_slots.h"

#include <algorithm>
#include <mutex>
#include <string>

#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

struct MappedSplatSlots::Shared {
  struct Slot {
    Splat* data = nullptr;  // the mapped region (null: no buffer yet)
    size_t capacity = 0;    // splats
    bool lendable = false;  // mapped, not lent, no GPU copy from it pending
    bool lent = false;      // a LentHostSplats holds it
  };
  std::mutex mutex;
  std::array<Slot, kSlots> slots;
  size_t wanted = 0;  // the largest count lend() found no slot large enough for
  size_t lentCount = 0;
  bool closed = false;  // stopLending: nothing lent any more
};

class MappedSplatSlots::Lender : public HostSplatLender {
 public:
  explicit Lender(std::shared_ptr<Shared> shared) : shared_(std::move(shared)) {}
  std::shared_ptr<LentHostSplats> lend(size_t count, const SplatLevels& levels) override {
    if (count == 0) return nullptr;
    std::lock_guard<std::mutex> lock(shared_->mutex);
    if (shared_->closed) return nullptr;
    int best = -1;  // the smallest lendable slot that holds `count`
    for (int i = 0; i < kSlots; ++i) {
      const Shared::Slot& slot = shared_->slots[i];
      if (slot.lendable && slot.capacity >= count &&
          (best < 0 || slot.capacity < shared_->slots[best].capacity))
        best = i;
    }
    if (best < 0) {
      bool fits = false;  // some slot is large enough, only busy now: nothing to grow
      for (const Shared::Slot& slot : shared_->slots) fits = fits || slot.capacity >= count;
      if (!fits) shared_->wanted = std::max(shared_->wanted, count);
      return nullptr;
    }
    Shared::Slot& slot = shared_->slots[best];
    std::shared_ptr<Shared> shared = shared_;
    // Made before the slot is marked: an allocation that throws leaves it lendable.
    auto lent = std::make_shared<LentHostSplats>(slot.data, count, levels, [shared, best] {
      std::lock_guard<std::mutex> giveBack(shared->mutex);
      shared->slots[best].lent = false;
    });
    slot.lendable = false;
    slot.lent = true;
    ++shared_->lentCount;
    return lent;
  }

 private:
  std::shared_ptr<Shared> shared_;
};

namespace {
// Read as well as write: hostData() promises splats a caller can read.
constexpr GLbitfield kMapFlags =
    GL_MAP_READ_BIT | GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
}  // namespace

bool MappedSplatSlots::supported() {
  return epoxy_gl_version() >= 44 || epoxy_has_gl_extension("GL_ARB_buffer_storage");
}

MappedSplatSlots::MappedSplatSlots(PinHostMemory pin)
    : pin_(std::move(pin)), shared_(std::make_shared<Shared>()) {}

MappedSplatSlots::~MappedSplatSlots() {
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->closed = true;
  }
  for (int i = 0; i < kSlots; ++i) release(i);
}

std::shared_ptr<HostSplatLender> MappedSplatSlots::lender() const {
  return std::make_shared<Lender>(shared_);
}

void MappedSplatSlots::stopLending() {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  shared_->closed = true;
  shared_->wanted = 0;
}

void MappedSplatSlots::release(int i) {
  SlotGl& gl = gl_[i];
  if (gl.copyDone) glDeleteSync(gl.copyDone);
  gl.copyDone = nullptr;
  if (gl.unpin) gl.unpin();  // before the memory is unmapped
  gl.unpin = nullptr;
  if (gl.buffer) glDeleteBuffers(1, &gl.buffer);  // unmaps it
  gl.buffer = 0;
  std::lock_guard<std::mutex> lock(shared_->mutex);
  shared_->slots[i].data = nullptr;
  shared_->slots[i].capacity = 0;
  shared_->slots[i].lendable = false;
}

bool MappedSplatSlots::copyFinished(int i) {
  SlotGl& gl = gl_[i];
  if (!gl.copyDone) return true;
  // Flushed, so that a fence still in the driver's queue signals without a swap.
  const GLenum state = glClientWaitSync(gl.copyDone, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  if (state == GL_TIMEOUT_EXPIRED) return false;
  if (state == GL_WAIT_FAILED) glFinish();  // no answer from the fence: wait for everything
  glDeleteSync(gl.copyDone);
  gl.copyDone = nullptr;
  return true;
}

void MappedSplatSlots::maintain() {
  bool grown = false;  // one buffer a frame: mapping (and pinning) hundreds of MB takes time
  for (int i = 0; i < kSlots; ++i) {
    size_t wanted, capacity;
    bool closed;
    {
      std::lock_guard<std::mutex> lock(shared_->mutex);
      const Shared::Slot& slot = shared_->slots[i];
      wanted = shared_->wanted;
      closed = shared_->closed;
      capacity = slot.capacity;
      if (slot.lent || (slot.lendable && !closed && (capacity >= wanted || grown))) continue;
      shared_->slots[i].lendable = false;  // ours while it is looked at or grown
    }
    if (!copyFinished(i)) continue;
    if (closed) {
      if (gl_[i].buffer) release(i);
      continue;
    }
    if (wanted > capacity && !grown) {
      grown = true;
      const size_t splats = wanted + wanted / 2;
      const size_t bytes = splats * sizeof(Splat);
      const uint64_t available = availableMemoryBytes();  // 0: unknown
      if (available > 0 && uint64_t(bytes) * kSlots > available / 4) {
        // Results this large take the worker's arrays (made and freed as they come) rather
        // than kSlots mappings kept for good.
        std::lock_guard<std::mutex> lock(shared_->mutex);
        shared_->wanted = 0;
      } else {
        release(i);
        while (glGetError() != GL_NO_ERROR) {
        }
        SlotGl& gl = gl_[i];
        glGenBuffers(1, &gl.buffer);
        glBindBuffer(GL_COPY_READ_BUFFER, gl.buffer);
        glBufferStorage(GL_COPY_READ_BUFFER, GLsizeiptr(bytes), nullptr, kMapFlags);
        void* data = glMapBufferRange(GL_COPY_READ_BUFFER, 0, GLsizeiptr(bytes), kMapFlags);
        const GLenum error = glGetError();
        glBindBuffer(GL_COPY_READ_BUFFER, 0);
        if (!data) {
          glDeleteBuffers(1, &gl.buffer);
          gl.buffer = 0;
          stopLending();
          throw Error("cannot map a GL buffer of " + std::to_string(bytes >> 20) +
                      " MiB for splats (GL error " + std::to_string(error) + ")");
        }
        std::string why = "the backend copies into pageable memory only";
        if (pin_) gl.unpin = pin_(data, bytes, &why);
        if (!gl.unpin && allPinned_) whyNotPinned_ = why;
        allPinned_ = allPinned_ && bool(gl.unpin);
        madeAny_ = true;
        std::lock_guard<std::mutex> lock(shared_->mutex);
        shared_->slots[i].data = static_cast<Splat*>(data);
        shared_->slots[i].capacity = splats;
        capacity = splats;
      }
    }
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->slots[i].lendable = capacity > 0 && !shared_->closed;
  }
}

int MappedSplatSlots::slotHolding(const Splat* data) const {
  if (!data) return -1;
  std::lock_guard<std::mutex> lock(shared_->mutex);
  for (int i = 0; i < kSlots; ++i)
    if (shared_->slots[i].data == data) return i;
  return -1;
}

bool MappedSplatSlots::holds(const SplatResource& splats) const {
  return slotHolding(splats.hostData()) >= 0;
}

bool MappedSplatSlots::copyInto(ViewportRenderer& renderer, const SplatResource& splats,
                                const SplatShape& shape) {
  const int i = slotHolding(splats.hostData());
  if (i < 0) return false;
  renderer.copySplats(gl_[i].buffer, splats.count(), shape);
  SlotGl& gl = gl_[i];
  if (gl.copyDone) glDeleteSync(gl.copyDone);
  gl.copyDone = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  ++copied_;
  return true;
}

size_t MappedSplatSlots::bytes() const {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  size_t total = 0;
  for (const Shared::Slot& slot : shared_->slots) total += slot.capacity * sizeof(Splat);
  return total;
}

size_t MappedSplatSlots::lentCount() const {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  return shared_->lentCount;
}

}  // namespace strata::ui
