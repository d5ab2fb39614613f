// Media plugins: loading by element name (seed 6.1, the facilities a medium
// provides) through the C ABI of include/asgard/medium_abi.h.
//
//   element "ASGARD" ──▶ medium_asgard.so in each directory of the search path
//                        ──dlsym(ASGARD_MEDIUM_ENTRY_SYMBOL)──▶ entry struct
//                        ──checks: abi_major, struct sizes, element name──▶ Medium
//
// Design: the element name decides the file name (lower case), so a host
// never loads plugins it does not need.  Every check failure is a sentence
// naming the file and what was wrong; a refused plugin is unloaded.  Lookups
// are cached, failures too, so a document with many subdocuments of a missing
// medium reports it once.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "asgard/medium_abi.h"

namespace asgard::host {

class Medium {
 public:
  ~Medium();
  Medium(const Medium&) = delete;
  Medium& operator=(const Medium&) = delete;

  const std::string& path() const { return path_; }
  const asgard_medium_entry& entry() const { return *entry_; }
  std::string element() const { return entry_->element_name; }
  // Interfaces; nullptr when the medium does not provide them.
  const asgard_storage_v1* storage() const { return storage_; }
  const asgard_node_v1* node() const { return node_; }
  const asgard_presentation_v1* presentation() const { return presentation_; }
  const asgard_rendition_v1* rendition() const { return rendition_; }
  // ABI 1.1: requests in the medium's own protocol to a node's slave.
  const asgard_node_rpc_v1* node_rpc() const { return node_rpc_; }

  // Copies the plugin's bytes into a string and frees them.
  std::string Take(asgard_bytes& bytes) const;

  // Loads one plugin file.  nullptr (with `error` set) when it cannot be
  // opened, has no entry symbol, is of another major ABI version, or its
  // structures are too small.  `element`, when not empty, must match.
  static std::unique_ptr<Medium> Load(const std::string& path, const std::string& element,
                                      std::string* error);

 private:
  Medium() = default;
  template <typename T>
  const T* Interface(uint32_t id) const;

  void* handle_ = nullptr;
  std::string path_;
  const asgard_medium_entry* entry_ = nullptr;
  const asgard_storage_v1* storage_ = nullptr;
  const asgard_node_v1* node_ = nullptr;
  const asgard_presentation_v1* presentation_ = nullptr;
  const asgard_rendition_v1* rendition_ = nullptr;
  const asgard_node_rpc_v1* node_rpc_ = nullptr;
};

class MediumRegistry {
 public:
  explicit MediumRegistry(std::vector<std::string> search_path);
  // $ASGARD_MEDIUM_PATH (colon-separated), then the build tree's
  // medium-plugin/ and the installed lib/asgard/ next to the executable.
  static std::vector<std::string> DefaultSearchPath();
  static std::string FileName(const std::string& element);  // "medium_asgard.so"

  // The medium for an element, or nullptr with the reason in `error`.
  Medium* Find(const std::string& element, std::string* error);
  const std::vector<std::string>& search_path() const { return search_path_; }

 private:
  std::vector<std::string> search_path_;
  std::map<std::string, std::unique_ptr<Medium>> loaded_;
  std::map<std::string, std::string> failed_;
};

}  // namespace asgard::host
