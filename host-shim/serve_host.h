// `dochost serve`: the editor server on the host's own medium nodes (issue 13:
// "editor traffic for an animation goes to the same asgard-core slave that
// draws its renditions, so the document and its editors are one state").
//
//   browser ══ WebSocket /ws?a=N ══▶ Hub (web/server/) ── NodeChannel ──┐
//   browser ── GET /frame?a=N&t=T ─▶ Hub worker ── HostDocument::Frame ─┤
//                                                                      ▼
//                        HostDocument item ── medium node (ABI 1.1 node_rpc, renditions)
//                                                   └── one asgard-core
//
// Each animation's Hub makes every call for its item on its one worker
// thread (editor requests and rendition frames alike), and the host document
// is made with room for a slave per animation, so no call touches another
// item.  A slave that dies is started again on the next action with the
// node's text, edits included; until then the picture is the last frame or
// the poster, with the reason.
#pragma once

#include <memory>
#include <string>

#include "host-shim/host_document.h"
#include "web/server/launch.h"
#include "web/server/slave_link.h"

namespace asgard::host {

// The editor's requests to one item's slave, through the medium's node_rpc.
class NodeChannel : public serve::SlaveChannel {
 public:
  NodeChannel(HostDocument& doc, size_t item) : doc_(doc), item_(item) {}
  bool running() const override;
  serve::SlaveAnswer Call(const std::string& method, const nlohmann::json& params) override;

 private:
  HostDocument& doc_;
  size_t item_;
};

// The document view's picture of an item at time t (its screen rendition).
serve::RenditionFrame RenditionOf(HostDocument& doc, Embedded& item, double t, bool handles);

// Gives each <ASGARD> animation of `doc` whose medium takes requests
// (node_rpc) a NodeChannel and a rendition; `doc` must outlive the server.
serve::AttachHost AttachTo(HostDocument& doc);

}  // namespace asgard::host
