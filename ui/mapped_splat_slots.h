// The editor's host path for device splats with no copy on the UI thread: GL buffers mapped for
// good (glBufferStorage with MAP_PERSISTENT | MAP_COHERENT), whose regions are lent to the
// preview worker (engine/ldi/lent_splats.h), which copies a result's splats from the device
// straight into one. The frame that shows them copies that buffer into the one it draws, on the
// GPU (glCopyBufferSubData), instead of uploading host memory. Where the backend can make the
// mapped memory page-locked (PinHostMemory: cudaHostRegister), the worker's copy is one DMA;
// otherwise the driver stages it.
//
// Memory: kSlots buffers, grown (one a frame, to 1.5 times the largest result that found none
// large enough) while all of them together stay under a quarter of the memory the system has;
// a result finds no region while the buffers grow, or when every one is held, and then takes
// the worker's own arrays.
//
// Threads: the lender (lender()) on any thread (the worker's); everything else on the UI thread
// with the GL context current. Regions are given back on any thread (a LentHostSplats
// destroyed); one is lent again only after the GPU finished the copy made from it (a fence).
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "engine/ldi/lent_splats.h"

namespace strata::ui {

class ViewportRenderer;
struct SplatShape;

// Makes `bytes` of host memory at `data` page-locked for the backend's copies into it; returns
// what undoes it (called before the memory goes), or an empty function where it cannot, with
// the reason in *why.
using PinHostMemory =
    std::function<std::function<void()>(void* data, size_t bytes, std::string* why)>;

class MappedSplatSlots {
 public:
  static constexpr int kSlots = 3;  // shown, waiting to be taken, being written
  // Whether the current context maps buffers persistently (GL 4.4 or ARB_buffer_storage).
  static bool supported();
  explicit MappedSplatSlots(PinHostMemory pin = {});
  // Unmaps every buffer. Destroy after every region was given back (the editor drops its
  // results and the worker first): a region still held would point at unmapped memory.
  ~MappedSplatSlots();
  MappedSplatSlots(const MappedSplatSlots&) = delete;
  MappedSplatSlots& operator=(const MappedSplatSlots&) = delete;

  // What the worker is given (PreviewWorker::setHostSplatLender): holds no GL object, so that
  // it may go on any thread.
  std::shared_ptr<HostSplatLender> lender() const;

  // Each frame: regions given back whose copy the GPU finished become lendable again; one slot
  // too small for the largest result that found none grows. Throws strata::Error when a buffer
  // cannot be mapped (the slots then lend no more: stopLending).
  void maintain();
  // No region is lent from now on; the buffers go as their regions come back.
  void stopLending();
  // Where `splats` lie in one of these buffers: `renderer` copies them into the buffer it draws
  // (on the GPU), the region is fenced behind that copy, and true is returned; false (nothing
  // done) for splats anywhere else.
  bool copyInto(ViewportRenderer& renderer, const SplatResource& splats, const SplatShape& shape);
  // Whether `splats` lie in one of these buffers.
  bool holds(const SplatResource& splats) const;

  // Whether any buffer was made yet, whether every one was page-locked, and if not why.
  bool made() const { return madeAny_; }
  bool pinned() const { return madeAny_ && allPinned_; }
  const std::string& whyNotPinned() const { return whyNotPinned_; }
  // Host memory mapped now, in bytes.
  size_t bytes() const;
  // Regions lent so far, and results copied into the drawn buffer from them (copyInto).
  size_t lentCount() const;
  size_t copiedCount() const { return copied_; }

 private:
  struct Shared;  // what the lender and the regions given back share with the UI
  class Lender;
  struct SlotGl {
    GLuint buffer = 0;
    GLsync copyDone = nullptr;
    std::function<void()> unpin;
  };
  int slotHolding(const Splat* data) const;
  void release(int slot);  // unpins, unmaps and deletes slot's buffer (neither lent nor fenced)
  // Whether slot's fence (if any) has signalled; deletes it then.
  bool copyFinished(int slot);

  PinHostMemory pin_;
  std::shared_ptr<Shared> shared_;
  std::array<SlotGl, kSlots> gl_;
  bool madeAny_ = false, allPinned_ = true;
  std::string whyNotPinned_;
  size_t copied_ = 0;
};

}  // namespace strata::ui
