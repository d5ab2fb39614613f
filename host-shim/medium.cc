// Plugin loading.  Design: dlopen with RTLD_NOW | RTLD_LOCAL (unresolved
// symbols fail at load, not at first use; plugins do not see each other), the
// entry struct read only within the size it declares, interface tables
// checked against the sizes this host was built with.
#include "host-shim/medium.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <sstream>

namespace asgard::host {

Medium::~Medium() {
  if (handle_) dlclose(handle_);
}

std::string Medium::Take(asgard_bytes& bytes) const {
  std::string s(bytes.data ? bytes.data : "", bytes.data ? bytes.size : 0);
  if (entry_->free_bytes) entry_->free_bytes(&bytes);
  return s;
}

template <typename T>
const T* Medium::Interface(uint32_t id) const {
  const void* p = entry_->get_interface ? entry_->get_interface(id) : nullptr;
  if (!p) return nullptr;
  const auto* t = static_cast<const T*>(p);
  return t->struct_size >= sizeof(T) ? t : nullptr;
}

std::unique_ptr<Medium> Medium::Load(const std::string& path, const std::string& element,
                                     std::string* error) {
  auto fail = [&](const std::string& why) -> std::unique_ptr<Medium> {
    if (error) *error = "medium plugin '" + path + "': " + why;
    return nullptr;
  };
  std::unique_ptr<Medium> m(new Medium);
  m->path_ = path;
  dlerror();
  m->handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!m->handle_) {
    const char* e = dlerror();
    return fail(std::string("cannot be loaded: ") + (e ? e : "unknown error"));
  }
  auto fn = reinterpret_cast<asgard_medium_entry_fn>(dlsym(m->handle_, ASGARD_MEDIUM_ENTRY_SYMBOL));
  if (!fn) return fail(std::string("has no entry point ") + ASGARD_MEDIUM_ENTRY_SYMBOL + "()");
  const asgard_medium_entry* e = fn();
  if (!e) return fail("its entry point returned nothing");
  if (e->struct_size < 3 * sizeof(uint32_t))
    return fail("its entry structure is too small to hold a version");
  if (e->abi_major != ASGARD_MEDIUM_ABI_MAJOR) {
    std::ostringstream s;
    s << "is built for medium ABI " << e->abi_major << "." << e->abi_minor
      << ", but this host speaks ABI " << ASGARD_MEDIUM_ABI_MAJOR << "." << ASGARD_MEDIUM_ABI_MINOR
      << " (the major versions must match); rebuild the plugin against this host";
    return fail(s.str());
  }
  if (e->struct_size < sizeof(asgard_medium_entry))
    return fail("its entry structure is smaller than ABI 1.0 requires");
  if (!e->element_name || !*e->element_name) return fail("it names no element");
  if (!element.empty() && element != e->element_name)
    return fail(std::string("it is for element <") + e->element_name + ">, not <" + element + ">");
  m->entry_ = e;
  m->storage_ = m->Interface<asgard_storage_v1>(ASGARD_IFACE_STORAGE);
  m->node_ = m->Interface<asgard_node_v1>(ASGARD_IFACE_NODE);
  m->presentation_ = m->Interface<asgard_presentation_v1>(ASGARD_IFACE_PRESENTATION);
  m->rendition_ = m->Interface<asgard_rendition_v1>(ASGARD_IFACE_RENDITION);
  m->node_rpc_ = m->Interface<asgard_node_rpc_v1>(ASGARD_IFACE_NODE_RPC);
  if (!m->storage_ || !m->storage_->decode || !m->storage_->encode)
    return fail("it provides no complete storage interface (seed 6.1 requires one)");
  // An interface with a missing function is treated as not provided.
  if (m->node_ &&
      !(m->node_->create && m->node_->destroy && m->node_->update && m->node_->simulate &&
        m->node_->command && m->node_->get_text && m->node_->get_status && m->node_->restart))
    m->node_ = nullptr;
  if (m->presentation_ && !m->presentation_->desired_size) m->presentation_ = nullptr;
  if (m->rendition_ && !(m->rendition_->create && m->rendition_->destroy &&
                         m->rendition_->set_flags && m->rendition_->frame))
    m->rendition_ = nullptr;
  if (m->node_rpc_ && !m->node_rpc_->call) m->node_rpc_ = nullptr;
  if (!m->node_) m->rendition_ = nullptr, m->presentation_ = nullptr, m->node_rpc_ = nullptr;
  return m;
}

MediumRegistry::MediumRegistry(std::vector<std::string> search_path)
    : search_path_(std::move(search_path)) {}

std::vector<std::string> MediumRegistry::DefaultSearchPath() {
  std::vector<std::string> path;
  if (const char* env = std::getenv("ASGARD_MEDIUM_PATH")) {
    std::istringstream in(env);
    std::string dir;
    while (std::getline(in, dir, ':'))
      if (!dir.empty()) path.push_back(dir);
  }
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    std::string dir(exe, static_cast<size_t>(n));
    dir = dir.substr(0, dir.rfind('/'));
    path.push_back(dir + "/../medium-plugin");
    path.push_back(dir + "/../../medium-plugin");
    path.push_back(dir + "/../lib/asgard");
  }
  return path;
}

std::string MediumRegistry::FileName(const std::string& element) {
  std::string lower = element;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return "medium_" + lower + ".so";
}

Medium* MediumRegistry::Find(const std::string& element, std::string* error) {
  if (auto it = loaded_.find(element); it != loaded_.end()) return it->second.get();
  if (auto it = failed_.find(element); it != failed_.end()) {
    if (error) *error = it->second;
    return nullptr;
  }
  const std::string file = FileName(element);
  std::string why;
  for (const std::string& dir : search_path_) {
    const std::string path = dir + "/" + file;
    if (access(path.c_str(), F_OK) != 0) continue;
    if (auto m = Medium::Load(path, element, &why)) {
      Medium* raw = m.get();
      loaded_[element] = std::move(m);
      return raw;
    }
    break;  // the first file found decides
  }
  if (why.empty()) {
    why = "no medium plugin for <" + element + "> (" + file + " is not in";
    for (const auto& d : search_path_) why += " " + d;
    why += search_path_.empty() ? " an empty search path)" : ")";
  }
  failed_[element] = why;
  if (error) *error = why;
  return nullptr;
}

}  // namespace asgard::host
