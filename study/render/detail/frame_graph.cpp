// Implementation of the frame graph (see frame_graph.h): declaration checks,
// reference-count culling, lifetimes, execution and the Graphviz export.
// Every misuse throws std::logic_error naming the pass and the resource.
#include <algorithm>
#include <ctime>
#include <span>
#include <sstream>
#include <stdexcept>

#include "study/render/detail/frame_graph.h"

namespace dtlab::render {

namespace {
[[noreturn]] void fail(const std::string& message) { throw std::logic_error("frame graph: " + message); }
}  // namespace

FrameGraph::FrameGraph() = default;
FrameGraph::~FrameGraph() = default;

std::vector<std::string> FrameReport::passes_run() const {
  std::vector<std::string> out;
  for (const auto& p : passes)
    if (!p.culled && p.ran.value_or(true)) out.push_back(p.name);
  return out;
}

std::uint32_t FrameGraph::push_pass(std::string name, std::unique_ptr<PassNode> node) {
  if (compiled_) fail("pass '" + name + "' added after compile()");
  node->name = std::move(name);
  passes_.push_back(std::move(node));
  return static_cast<std::uint32_t>(passes_.size() - 1);
}

std::uint32_t FrameGraph::new_node(std::uint32_t resource, int writer, int previous) {
  nodes_.push_back(Node{resource, resources_[resource].version, writer, 0, previous});
  return static_cast<std::uint32_t>(nodes_.size() - 1);
}

const FrameGraph::Node& FrameGraph::checked(Handle h, std::uint32_t pass, const char* action) const {
  const std::string& pname = passes_[pass]->name;
  if (!h.valid() || h.node_ >= nodes_.size())
    fail("pass '" + pname + "' " + action + " an invalid (default or foreign) handle");
  const Node& n = nodes_[h.node_];
  const Resource& r = resources_[n.resource];
  if (n.resource < stage_resource_ && r.kind != Resource::Kind::imported)
    fail("pass '" + pname + "' " + action + " '" + r.name +
         "' of a flushed stage: its passes ran and its transients are freed (only imported targets carry over a flush())");
  if (n.version != r.version)
    fail("pass '" + pname + "' " + action + " '" + r.name + "' through a stale handle (version " +
         std::to_string(n.version) + ", current " + std::to_string(r.version) +
         "): use the handle returned by the last write()");
  return n;
}

bool FrameGraph::declares(std::uint32_t pass, std::uint32_t node) const {
  const PassNode& p = *passes_[pass];
  return std::find(p.reads.begin(), p.reads.end(), node) != p.reads.end() ||
         std::find(p.writes.begin(), p.writes.end(), node) != p.writes.end() ||
         (p.condition && *p.condition == node);
}

Handle FrameGraph::import_target(std::string name, const ImportedTarget& target) {
  Resource r;
  r.name = std::move(name);
  r.kind = Resource::Kind::imported;
  r.imported = target;
  r.desc = TextureDesc{target.width, target.height, TextureFormat::rgba8, false};
  resources_.push_back(std::move(r));
  return Handle(new_node(static_cast<std::uint32_t>(resources_.size() - 1), -1));
}

const std::string& FrameGraph::name_of(Handle h) const {
  if (!h.valid() || h.node_ >= nodes_.size()) fail("name_of() on an invalid handle");
  return resources_[nodes_[h.node_].resource].name;
}

// --- Builder ---------------------------------------------------------------------------

Handle FrameGraph::Builder::create(std::string name, const TextureDesc& desc) {
  if (desc.width <= 0 || desc.height <= 0)
    fail("pass '" + graph_.passes_[pass_]->name + "' creates '" + name + "' with size " +
         std::to_string(desc.width) + "x" + std::to_string(desc.height));
  Resource r;
  r.name = std::move(name);
  r.desc = desc;
  graph_.resources_.push_back(std::move(r));
  return Handle(graph_.new_node(static_cast<std::uint32_t>(graph_.resources_.size() - 1), -1));
}

Handle FrameGraph::Builder::create_query(std::string name) {
  Resource r;
  r.name = std::move(name);
  r.kind = Resource::Kind::query;
  graph_.resources_.push_back(std::move(r));
  return Handle(graph_.new_node(static_cast<std::uint32_t>(graph_.resources_.size() - 1), -1));
}

Handle FrameGraph::Builder::read(Handle h) {
  const Node& n = graph_.checked(h, pass_, "reads");
  const Resource& r = graph_.resources_[n.resource];
  if (n.version == 0 && r.kind != Resource::Kind::imported)
    fail("pass '" + graph_.passes_[pass_]->name + "' reads '" + r.name + "' before any pass wrote it");
  auto& reads = graph_.passes_[pass_]->reads;
  if (std::find(reads.begin(), reads.end(), h.node_) == reads.end()) reads.push_back(h.node_);
  return h;
}

Handle FrameGraph::Builder::write(Handle h) {
  const Node& n = graph_.checked(h, pass_, "writes");
  const std::uint32_t resource = n.resource;
  Resource& r = graph_.resources_[resource];
  ++r.version;
  if (r.kind == Resource::Kind::imported) graph_.passes_[pass_]->side_effect = true;  // a root
  const std::uint32_t node = graph_.new_node(resource, static_cast<int>(pass_), static_cast<int>(h.node_));
  graph_.passes_[pass_]->writes.push_back(node);
  return Handle(node);
}

void FrameGraph::Builder::condition(Handle query) {
  const Node& n = graph_.checked(query, pass_, "is conditional on");
  const Resource& r = graph_.resources_[n.resource];
  if (r.kind != Resource::Kind::query)
    fail("pass '" + graph_.passes_[pass_]->name + "' is conditional on '" + r.name + "', which is not a query");
  if (n.version == 0)
    fail("pass '" + graph_.passes_[pass_]->name + "' is conditional on '" + r.name + "' before any pass wrote it");
  graph_.passes_[pass_]->condition = query.node_;
}

void FrameGraph::Builder::side_effect() { graph_.passes_[pass_]->side_effect = true; }

// --- compile: cull by reference count ----------------------------------------------------

void FrameGraph::compile() {
  if (compiled_) fail("compile() called twice");
  compiled_ = true;
  const auto stage = [this] {
    return std::span<std::unique_ptr<PassNode>>(passes_).subspan(stage_pass_);
  };
  // A conditional pass that does not run leaves what it writes as it was, so whoever reads its
  // output may see the previous version: each of its writes also reads the version it replaces.
  for (auto& p : stage()) {
    if (!p->condition) continue;
    for (auto w : p->writes) {
      const int prev = nodes_[w].previous;
      if (prev >= 0 && std::find(p->reads.begin(), p->reads.end(), static_cast<std::uint32_t>(prev)) == p->reads.end())
        p->reads.push_back(static_cast<std::uint32_t>(prev));
    }
  }
  for (auto& n : nodes_) n.refcount = 0;
  for (auto& p : stage()) {
    p->refcount = static_cast<int>(p->writes.size()) + (p->side_effect ? 1 : 0);
    for (auto r : p->reads) ++nodes_[r].refcount;
    if (p->condition) ++nodes_[*p->condition].refcount;
  }
  std::vector<std::uint32_t> stack;
  for (std::uint32_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].refcount == 0) stack.push_back(i);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (n.writer < static_cast<int>(stage_pass_)) continue;  // created, imported, or written by a flushed stage
    PassNode& p = *passes_[static_cast<std::size_t>(n.writer)];
    if (--p.refcount > 0 || p.side_effect) continue;
    p.culled = true;
    auto release = [&](std::uint32_t r) {
      if (--nodes_[r].refcount == 0) stack.push_back(r);
    };
    for (auto r : p.reads) release(r);
    if (p.condition) release(*p.condition);
  }
  // Lifetimes of transient resources over the surviving passes.
  for (std::uint32_t pi = stage_pass_; pi < passes_.size(); ++pi) {
    const PassNode& p = *passes_[pi];
    if (p.culled) continue;
    auto touch = [&](std::uint32_t node) {
      Resource& r = resources_[nodes_[node].resource];
      if (r.first_pass < 0) r.first_pass = static_cast<int>(pi);
      r.last_pass = static_cast<int>(pi);
    };
    for (auto n : p.reads) touch(n);
    for (auto n : p.writes) touch(n);
    if (p.condition) touch(*p.condition);
  }
}

// --- execute ----------------------------------------------------------------------------

void FrameGraph::execute(FrameGraphBackend& backend, bool profile, const DrawCounts* counts) {
  if (!compiled_) fail("execute() before compile()");
  if (executed_) fail("execute() called twice");
  executed_ = true;
  if (stage_pass_ == 0) backend.drain_errors();  // errors from before this frame are not ours
  pass_ms_.resize(passes_.size(), 0.0);
  pass_counts_.resize(passes_.size(), DrawCounts{});
  if (profile) backend.finish();
  for (std::uint32_t pi = stage_pass_; pi < passes_.size(); ++pi) {
    PassNode& p = *passes_[pi];
    if (p.culled) continue;
    for (auto& r : resources_) {
      if (r.first_pass != static_cast<int>(pi) || r.gl_name != 0) continue;
      if (r.kind == Resource::Kind::texture) r.gl_name = backend.acquire_texture(r.desc);
      if (r.kind == Resource::Kind::query) {
        r.gl_name = backend.acquire_query();
        queries_used_.push_back(r.gl_name);
      }
    }
    PassResources res(*this, pi, backend);
    timespec cpu0{};
    DrawCounts before;
    if (profile) {
      if (counts) before = *counts;
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu0);
    }
    if (p.condition) {
      const unsigned q = resources_[nodes_[*p.condition].resource].gl_name;
      pass_query_.emplace_back(pi, q);
      backend.begin_condition(q);
      try {
        p.run(res);
      } catch (...) {  // a GlFailure inside (boundary.h): leave no conditional rendering behind
        backend.end_condition();
        throw;
      }
      backend.end_condition();
    } else {
      p.run(res);
    }
    if (profile) {
      backend.finish();
      timespec cpu1{};
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu1);
      pass_ms_[pi] = static_cast<double>(cpu1.tv_sec - cpu0.tv_sec) * 1e3 + static_cast<double>(cpu1.tv_nsec - cpu0.tv_nsec) * 1e-6;
      if (counts) pass_counts_[pi] = {counts->draws - before.draws, counts->triangles - before.triangles};
    }
    for (auto& e : backend.drain_errors()) errors_.push_back("pass '" + p.name + "': " + e);
    for (auto& r : resources_) {
      if (r.last_pass != static_cast<int>(pi) || r.kind != Resource::Kind::texture || r.gl_name == 0) continue;
      backend.release_texture(r.desc, r.gl_name);
      r.gl_name = 0;
    }
  }
  executed_passes_ = static_cast<std::uint32_t>(passes_.size());
}

void FrameGraph::flush(FrameGraphBackend& backend, bool profile, const DrawCounts* counts) {
  compile();
  execute(backend, profile, counts);
  stage_pass_ = static_cast<std::uint32_t>(passes_.size());
  stage_resource_ = static_cast<std::uint32_t>(resources_.size());
  stage_starts_.push_back(stage_pass_);
  compiled_ = false;
  executed_ = false;
}

std::optional<bool> FrameGraph::answer(Handle query, FrameGraphBackend& backend, bool wait) const {
  if (executed_passes_ == 0 || !query.valid() || query.node_ >= nodes_.size()) return std::nullopt;
  const Resource& r = resources_[nodes_[query.node_].resource];
  if (r.kind != Resource::Kind::query || r.gl_name == 0) return std::nullopt;  // culled, or after report()
  return backend.query_any(r.gl_name, wait);
}

FrameReport FrameGraph::report(FrameGraphBackend& backend, bool wait_for_queries) {
  FrameReport out;
  for (std::uint32_t pi = 0; pi < passes_.size(); ++pi) {
    const PassNode& p = *passes_[pi];
    PassRecord rec{p.name, p.culled, p.condition.has_value(), std::nullopt, pi < pass_ms_.size() ? pass_ms_[pi] : 0.0};
    if (pi < pass_counts_.size()) {
      rec.draws = pass_counts_[pi].draws;
      rec.triangles = pass_counts_[pi].triangles;
    }
    if (p.culled || pi >= executed_passes_) {
      rec.ran = false;
    } else if (!p.condition) {
      rec.ran = true;
    } else {
      for (auto& [pass, q] : pass_query_)
        if (pass == pi) rec.ran = backend.query_any(q, wait_for_queries);
    }
    out.passes.push_back(std::move(rec));
  }
  out.gl_errors = errors_;
  for (unsigned q : queries_used_) backend.release_query(q);
  queries_used_.clear();
  for (auto& r : resources_)
    if (r.kind == Resource::Kind::query) r.gl_name = 0;
  return out;
}

std::string FrameGraph::graphviz() const {
  std::ostringstream o;
  o << "digraph framegraph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n";
  // A frame run in stages (flush()) shows each stage as a cluster, in order.
  const bool staged = stage_starts_.size() > 1 && stage_starts_[1] < passes_.size();
  for (std::size_t si = 0; si < stage_starts_.size(); ++si) {
    const std::uint32_t end = si + 1 < stage_starts_.size() ? stage_starts_[si + 1] : static_cast<std::uint32_t>(passes_.size());
    if (staged) o << "  subgraph cluster_stage" << si << " {\n    label=\"stage " << si + 1 << "\";\n";
    for (std::uint32_t pi = stage_starts_[si]; pi < end; ++pi) {
      const PassNode& p = *passes_[pi];
      o << (staged ? "    P" : "  P") << pi << " [shape=box, style=filled, fillcolor=\""
        << (p.culled ? "grey80" : "orange") << "\", label=\"" << p.name << (p.condition ? "\\n(conditional)" : "")
        << "\"];\n";
    }
    if (staged) o << "  }\n";
  }
  for (std::uint32_t ni = 0; ni < nodes_.size(); ++ni) {
    const Resource& r = resources_[nodes_[ni].resource];
    o << "  R" << ni << " [shape=ellipse, label=\"" << r.name << "\\nv" << nodes_[ni].version << "\"];\n";
  }
  for (std::uint32_t pi = 0; pi < passes_.size(); ++pi) {
    const PassNode& p = *passes_[pi];
    for (auto n : p.reads) o << "  R" << n << " -> P" << pi << ";\n";
    if (p.condition) o << "  R" << *p.condition << " -> P" << pi << " [style=dashed];\n";
    for (auto n : p.writes) o << "  P" << pi << " -> R" << n << " [color=red];\n";
  }
  o << "}\n";
  return o.str();
}

// --- PassResources ------------------------------------------------------------------------

std::uint32_t PassResources::node_checked(Handle h, const char* what) const {
  const std::string& pname = graph_.passes_[pass_]->name;
  if (!h.valid() || h.node_ >= graph_.nodes_.size()) fail("pass '" + pname + "' asks for the " + what + " of an invalid handle");
  if (!graph_.declares(pass_, h.node_))
    fail("pass '" + pname + "' uses '" + graph_.resources_[graph_.nodes_[h.node_].resource].name +
         "' which its setup did not declare");
  return graph_.nodes_[h.node_].resource;
}

unsigned PassResources::texture(Handle h) const {
  const auto& r = graph_.resources_[node_checked(h, "texture")];
  if (r.kind != FrameGraph::Resource::Kind::texture)
    fail("pass '" + pass_name() + "' asks for '" + r.name + "' as a texture, but it is not one");
  return r.gl_name;
}

unsigned PassResources::query(Handle h) const {
  const auto& r = graph_.resources_[node_checked(h, "query")];
  if (r.kind != FrameGraph::Resource::Kind::query)
    fail("pass '" + pass_name() + "' asks for '" + r.name + "' as a query, but it is not one");
  return r.gl_name;
}

const TextureDesc& PassResources::desc(Handle h) const { return graph_.resources_[node_checked(h, "description")].desc; }

unsigned PassResources::framebuffer(std::vector<Handle> color, Handle depth) const {
  using Kind = FrameGraph::Resource::Kind;
  if (color.size() == 1 && !depth.valid()) {
    const auto& r = graph_.resources_[node_checked(color[0], "framebuffer")];
    if (r.kind == Kind::imported) return r.imported.framebuffer;
  }
  std::vector<unsigned> names;
  for (Handle h : color) {
    const auto& r = graph_.resources_[node_checked(h, "framebuffer")];
    if (r.kind != Kind::texture) fail("pass '" + pass_name() + "' attaches '" + r.name + "', which is not a texture");
    names.push_back(r.gl_name);
  }
  unsigned depth_name = 0;
  TextureFormat depth_format = TextureFormat::depth24_stencil8;
  if (depth.valid()) {
    const auto& r = graph_.resources_[node_checked(depth, "framebuffer")];
    if (r.kind != Kind::texture || (r.desc.format != TextureFormat::depth24_stencil8 && r.desc.format != TextureFormat::depth32f))
      fail("pass '" + pass_name() + "' attaches '" + r.name + "' as depth, but it is not a depth texture");
    depth_name = r.gl_name;
    depth_format = r.desc.format;
  }
  return backend_.framebuffer(names, depth_name, depth_format);
}

const std::string& PassResources::pass_name() const { return graph_.passes_[pass_]->name; }

}  // namespace dtlab::render
