// CUDA-GL interop for the editor's splats (gpu/interop, app/cuda_gl_splat_copier): the CUDA
// backend's splats copied device to device into a GL buffer hold exactly the CPU reference's
// bytes, and the editor draws the same pixels through interop as through the host upload path
// and as with the CPU backend. Labelled gpu and display: needs a CUDA device and a GL context on
// it (on the lent GPU: Xvfb with NVIDIA's GLX). Skips, saying why, otherwise; on Mesa the editor
// must have chosen the host upload path, which is checked before skipping.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>

#include "app/cuda_gl_splat_copier.h"
#include "app/cuda_host_pinning.h"
#include "engine/document/commands.h"
#include "engine/eval/cpu_backend.h"
#include "gpu/cuda_backend.h"
#include "gpu/interop/gl_splat_buffer.h"
#include "tests/support/scene_builder.h"
#include "ui/editor.h"
#include "ui/editor_actions.h"
#include "ui/gl_window.h"

namespace strata::test {
namespace {

#define REQUIRE_CUDA_AND_DISPLAY()                                                    \
  do {                                                                                \
    std::string why;                                                                  \
    if (!cudaDeviceAvailable(&why)) GTEST_SKIP() << "no CUDA device (" << why << ")"; \
    if (!ui::displayAvailable(&why)) GTEST_SKIP() << "no display (" << why << ")";    \
  } while (0)

bool onMesa(const std::string& glDescription) {
  return glDescription.find("llvmpipe") != std::string::npos ||
         glDescription.find("Mesa") != std::string::npos;
}

TEST(CudaGlInterop, CopiedBufferHoldsTheCpuSplatsBitForBit) {
  REQUIRE_CUDA_AND_DISPLAY();
  ui::GlWindow window(64, 64, "interop test", false);
  Scene scene = makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2)}), 96);
  Progress progress;
  Evaluator onCpu(std::make_shared<CpuBackend>()), onGpu(makeCudaBackend());
  SplatsHandle expected =
      onCpu.backend().splats(onCpu.evaluate(scene, {}, progress).root, progress);
  SplatsHandle device = onGpu.backend().splats(onGpu.evaluate(scene, {}, progress).root, progress);
  ASSERT_GT(expected->count(), 1000u);
  ASSERT_TRUE(CudaGlSplatBuffer::canCopy(*device));
  ASSERT_FALSE(CudaGlSplatBuffer::canCopy(*expected));

  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(device->bytes() + 4096), nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  CudaGlSplatBuffer interop;
  try {
    interop.attach(buffer);
  } catch (const Error& e) {
    glDeleteBuffers(1, &buffer);
    if (onMesa(window.description()))
      GTEST_SKIP() << "GL runs on " << window.description() << ": " << e.what();
    FAIL() << window.description() << ": " << e.what();
  }
  interop.copy(*device);
  std::vector<Splat> readBack(device->count());
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glGetBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(device->bytes()), readBack.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  EXPECT_EQ(std::memcmp(readBack.data(), expected->hostData(), expected->bytes()), 0);
  // Too small a buffer is refused, not overrun.
  interop.detach();
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, 64, nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  interop.attach(buffer);
  EXPECT_THROW(interop.copy(*device), Error);
  interop.detach();
  glDeleteBuffers(1, &buffer);
}

// The editor on `makeBackend` (with the interop copier when `interop`, else the host path with
// its mapped buffers page-locked), a small difference evaluated at 95, then at 96 (on the host
// path the second result goes into a mapped buffer grown for the first), rendered from the front
// at 320 x 200; *mapped: the results that went through mapped buffers.
std::vector<uint8_t> renderInEditor(std::function<std::shared_ptr<Backend>()> makeBackend,
                                    bool interop, std::string* transfer, std::string* gl,
                                    size_t* mapped) {
  ui::EditorOptions options;
  options.makeBackend = std::move(makeBackend);
  if (interop) options.makeSplatCopier = makeCudaGlSplatCopier;
  if (!interop) options.pinHostMemory = makeCudaHostPinning();
  options.visible = false;
  options.width = 1280;  // room for the panels around the view
  options.height = 800;
  ui::Editor editor(options);
  ui::EditorState& state = editor.state();
  NodeId block = ui::addPrimitive(state, NodeKind::Box);
  ui::clearSelection(state);
  NodeId ball = ui::addPrimitive(state, NodeKind::Sphere);
  EXPECT_TRUE(ui::guarded(state, [&] {
    PrimitiveParams p;
    p.size = glm::dvec3(2.0);
    state.document.setParams(block, p);
    p.radius = 1.2;
    state.document.setParams(ball, p);
    state.document.setColor(block, glm::vec3(0.2f, 0.5f, 0.9f));
  }));
  state.selection = {block, ball};
  ui::groupSelection(state, NodeKind::Difference);
  ui::clearSelection(state);
  state.showGrid = false;
  ui::setResolution(state, 95);
  EXPECT_TRUE(editor.waitForPreview(120.0)) << state.previewError;
  ui::setResolution(state, 96);
  EXPECT_TRUE(editor.waitForPreview(120.0)) << state.previewError;
  editor.camera().setAxisView(ui::AxisView::Front);
  editor.viewAll();
  for (int i = 0; i < 2; ++i) editor.frame();
  *transfer = state.splatTransfer;
  *gl = state.glDescription;
  *mapped = editor.resultsInMappedBuffers();
  return editor.renderViewport(320, 200);
}

TEST(CudaGlInterop, EditorDrawsTheSamePixelsThroughInteropAsThroughTheHost) {
  REQUIRE_CUDA_AND_DISPLAY();
  std::string transfer, gl;
  size_t mapped = 0;
  std::vector<uint8_t> viaInterop =
      renderInEditor([] { return makeCudaBackend(); }, true, &transfer, &gl, &mapped);
  if (transfer != "CUDA-GL interop") {
    ASSERT_EQ(transfer.rfind("host upload", 0), 0u) << transfer;  // the fallback, named
    if (onMesa(gl)) GTEST_SKIP() << "GL runs on " << gl << ": " << transfer;
    FAIL() << "interop unavailable on " << gl << ": " << transfer;
  }
  std::string hostTransfer, cpuTransfer;
  std::vector<uint8_t> viaHost =
      renderInEditor([] { return makeCudaBackend(); }, false, &hostTransfer, &gl, &mapped);
  // The worker's copy of the second result into a mapped GL buffer (by DMA where the driver
  // let CUDA page-lock it: on the H200's driver it does), copied from there on the GPU.
  EXPECT_NE(hostTransfer.find("into mapped GL buffers"), std::string::npos) << hostTransfer;
  if (hostTransfer.find("by DMA") == std::string::npos)
    std::printf("note: the mapped splat buffers were not page-locked on %s\n", gl.c_str());
  EXPECT_GE(mapped, 1u);
  std::vector<uint8_t> onCpu = renderInEditor([] { return std::make_shared<CpuBackend>(); }, false,
                                              &cpuTransfer, &gl, &mapped);
  EXPECT_EQ(mapped, 0u) << "host splats are uploaded as they are";
  ASSERT_EQ(viaInterop.size(), viaHost.size());
  EXPECT_TRUE(viaInterop == viaHost) << "interop and host upload draw different pixels";
  EXPECT_TRUE(viaInterop == onCpu) << "CUDA and CPU splats draw different pixels";
  size_t lit = 0;
  for (size_t i = 0; i < viaInterop.size(); i += 4) lit += viaInterop[i + 2] > 150 ? 1 : 0;
  EXPECT_GT(lit, 2000u) << "the part is on screen";
}

}  // namespace
}  // namespace strata::test
