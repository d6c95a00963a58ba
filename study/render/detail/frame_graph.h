// Internal: a frame graph in the manner of Filament's (filament/src/fg): each pass is a
// data struct of resource handles, a setup function that only declares what
// the pass creates, reads and writes, and an execute function that only uses
// what was declared. compile() culls, by reference count, every pass whose
// outputs nothing reads (roots: passes that write an imported target or that
// declare a side effect); execute() runs the rest in declaration order, which
// is a dependency order because a handle exists only once the pass creating
// or writing it has been declared. Transient textures live from their first
// to their last user and come from a pool, so a frame allocates nothing once
// warm. A pass may be conditional on an occlusion query another pass wrote;
// it then runs inside GL conditional rendering and the report says whether it
// ran; each of its writes counts as a read of the version it replaces (when it
// does not run, readers see that version). A frame whose later passes depend
// on what its earlier passes computed on the CPU (occlusion culling reads its
// map back and drops hidden objects from the lists the method's passes are
// declared over) runs in stages: flush() compiles and executes the passes
// declared so far, and later passes may touch only imported targets and their
// own resources; the report, the profile and the Graphviz export show every
// stage. Guarantees: a stale handle (one that a later write() superseded), an
// undeclared access or a transient of an earlier stage fails loudly with the
// pass's and the resource's names.
// Never: touches GL itself (the FrameGraphBackend does), or runs a culled pass.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/render/frame_report.h"

namespace dtlab::render {

enum class TextureFormat { rgba8, rgba16f, rgba32f, r8, r16f, r32f, r32ui, depth24_stencil8, depth32f };

struct TextureDesc {
  int width = 0;
  int height = 0;
  TextureFormat format = TextureFormat::rgba8;
  bool linear = false;  // bilinear sampling (else nearest); clamp to edge either way
  bool operator==(const TextureDesc&) const = default;
};

// A versioned reference to a resource of one FrameGraph. Copyable; becomes
// stale when a pass writes the resource (write() returns the successor).
class Handle {
 public:
  Handle() = default;
  bool valid() const { return node_ != kNone; }  // false for a default-constructed handle
  bool operator==(const Handle&) const = default;

 private:
  friend class FrameGraph;
  friend class PassResources;
  static constexpr std::uint32_t kNone = 0xffffffffu;
  explicit Handle(std::uint32_t node) : node_(node) {}
  std::uint32_t node_ = kNone;
};

// The GL side of the graph: allocation, framebuffers, conditions, errors.
// detail/gl_backend.h implements it with OpenGL; graph unit tests record calls.
class FrameGraphBackend {
 public:
  virtual ~FrameGraphBackend() = default;
  virtual unsigned acquire_texture(const TextureDesc& desc) = 0;  // a texture of that desc, contents undefined
  virtual void release_texture(const TextureDesc& desc, unsigned name) = 0;  // back to the pool
  virtual unsigned acquire_query() = 0;                          // an occlusion query object
  virtual void release_query(unsigned name) = 0;
  // A framebuffer with these colour textures (in order) and depth(/stencil) texture attached.
  virtual unsigned framebuffer(const std::vector<unsigned>& color, unsigned depth, TextureFormat depth_format) = 0;
  virtual void begin_condition(unsigned query) = 0;  // glBeginConditionalRender(query, wait)
  virtual void end_condition() = 0;
  virtual std::optional<bool> query_any(unsigned query, bool wait) = 0;  // samples passed? nullopt: not ready
  virtual std::vector<std::string> drain_errors() = 0;  // GL errors since the last call
  virtual void finish() = 0;                           // glFinish (per-pass profiling only)
};

class FrameGraph;

// What a pass's execute function may touch: only resources its setup declared.
class PassResources {
 public:
  unsigned texture(Handle h) const;  // GL name of a declared texture
  unsigned query(Handle h) const;    // GL name of a declared query
  const TextureDesc& desc(Handle h) const;  // a declared texture's description
  // A framebuffer with the declared textures attached (an imported target's own framebuffer
  // when `color` is that single imported handle).
  unsigned framebuffer(std::vector<Handle> color, Handle depth = {}) const;
  const std::string& pass_name() const;

 private:
  friend class FrameGraph;
  PassResources(const FrameGraph& g, std::uint32_t pass, FrameGraphBackend& b) : graph_(g), pass_(pass), backend_(b) {}
  std::uint32_t node_checked(Handle h, const char* what) const;
  const FrameGraph& graph_;
  std::uint32_t pass_;
  FrameGraphBackend& backend_;
};

class FrameGraph {
 public:
  class Builder {
   public:
    Handle create(std::string name, const TextureDesc& desc);  // a transient texture; write() it before reading
    Handle create_query(std::string name);                     // a transient occlusion query; write() it
    Handle read(Handle h);    // declares a read; returns h
    Handle write(Handle h);   // declares a write; returns the new version (h becomes stale)
    void condition(Handle query);  // run only if `query` saw samples (declares a read)
    void side_effect();            // keep this pass even if nothing reads its outputs

   private:
    friend class FrameGraph;
    Builder(FrameGraph& g, std::uint32_t pass) : graph_(g), pass_(pass) {}
    FrameGraph& graph_;
    std::uint32_t pass_;
  };

  FrameGraph();
  ~FrameGraph();
  FrameGraph(const FrameGraph&) = delete;
  FrameGraph& operator=(const FrameGraph&) = delete;

  // Declares a pass. `setup(Builder&, Data&)` runs now; `execute(const Data&, PassResources&)`
  // runs in execute() unless the pass is culled. Returns the pass's data (valid for the graph's life).
  template <class Data, class Setup, class Execute>
  const Data& add_pass(std::string name, Setup&& setup, Execute&& execute) {
    auto node = std::make_unique<TypedPass<Data>>();
    Data& data = node->data;
    node->run = [fn = std::forward<Execute>(execute), &data](PassResources& r) { fn(static_cast<const Data&>(data), r); };
    const std::uint32_t index = push_pass(std::move(name), std::move(node));
    Builder builder(*this, index);
    setup(builder, data);
    return data;
  }

  Handle import_target(std::string name, const ImportedTarget& target);  // writes to it make a pass a root
  const std::string& name_of(Handle h) const;  // the resource's name, for messages

  void compile();                              // culls the stage; call once, after its last add_pass
  // Runs the stage's surviving passes, then frees their transients. With `profile`, a glFinish
  // after each pass gives per-pass process CPU times (llvmpipe renders on CPU threads; debugging
  // only), and `counts` (if given) read before and after each pass gives its draws and triangles.
  void execute(FrameGraphBackend& backend, bool profile = false, const DrawCounts* counts = nullptr);
  // Ends a stage: compile() and execute() the passes declared since the last flush, then opens
  // the next stage, whose passes may not touch this stage's transient textures and queries
  // (they are freed); imported targets carry over. For a pass whose results the CPU needs before
  // the next passes can be declared (a readback).
  void flush(FrameGraphBackend& backend, bool profile = false, const DrawCounts* counts = nullptr);
  // After execute() and before report(): did `query` see samples? nullopt if the query was culled
  // or (without `wait`) its answer is not ready.
  std::optional<bool> answer(Handle query, FrameGraphBackend& backend, bool wait) const;
  // After execute() (and, to get every answer, after glFinish): who ran, GL errors.
  FrameReport report(FrameGraphBackend& backend, bool wait_for_queries);
  std::string graphviz() const;                // the graph in dot syntax; culled passes grey

 private:
  struct PassNode {
    virtual ~PassNode() = default;
    std::string name;
    std::function<void(PassResources&)> run;
    std::vector<std::uint32_t> reads, writes;  // resource-version nodes
    std::optional<std::uint32_t> condition;    // query node
    bool side_effect = false;
    int refcount = 0;
    bool culled = false;
  };
  template <class Data>
  struct TypedPass final : PassNode {
    Data data{};
  };
  struct Resource {
    std::string name;
    enum class Kind { texture, query, imported } kind = Kind::texture;
    TextureDesc desc;
    ImportedTarget imported;
    int version = 0;
    unsigned gl_name = 0;  // while allocated
    int first_pass = -1, last_pass = -1;  // lifetime over surviving passes
  };
  struct Node {  // one version of a resource
    std::uint32_t resource = 0;
    int version = 0;
    int writer = -1;  // pass that produced this version (-1: created or imported)
    int refcount = 0;
    int previous = -1;  // the version this one replaced (-1: the first)
  };

  std::uint32_t push_pass(std::string name, std::unique_ptr<PassNode> node);
  std::uint32_t new_node(std::uint32_t resource, int writer, int previous = -1);
  // h's node for `pass` to `action` (read, write, ...); fails on a stale, foreign or invalid
  // handle, or a transient of a flushed stage.
  const Node& checked(Handle h, std::uint32_t pass, const char* action) const;
  bool declares(std::uint32_t pass, std::uint32_t node) const;

  friend class Builder;
  friend class PassResources;
  std::vector<std::unique_ptr<PassNode>> passes_;
  std::vector<Resource> resources_;
  std::vector<Node> nodes_;
  std::vector<unsigned> queries_used_;  // query names held until report()
  std::vector<std::string> errors_;     // GL errors, prefixed with the pass
  std::vector<double> pass_ms_;         // per pass, when profiled
  std::vector<DrawCounts> pass_counts_;  // per pass, when profiled with counts
  std::vector<std::pair<std::uint32_t, unsigned>> pass_query_;  // conditional pass -> query name
  bool compiled_ = false;  // the current stage's
  bool executed_ = false;  // the current stage's
  std::uint32_t executed_passes_ = 0;  // passes [0, this) belong to executed stages
  // The current stage's first pass and first resource; earlier ones belong to flushed stages.
  std::uint32_t stage_pass_ = 0, stage_resource_ = 0;
  std::vector<std::uint32_t> stage_starts_{0};  // each stage's first pass (Graphviz clusters)
};

}  // namespace dtlab::render
