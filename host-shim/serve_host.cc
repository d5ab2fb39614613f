#include "host-shim/serve_host.h"

namespace asgard::host {

bool NodeChannel::running() const {
  const Embedded& item = doc_.items()[item_];
  return item.node && item.status.pid > 0 && item.status.state != ASGARD_NODE_CRASHED &&
         item.status.state != ASGARD_NODE_HUNG;
}

serve::SlaveAnswer NodeChannel::Call(const std::string& method, const nlohmann::json& params) {
  Embedded& item = doc_.items()[item_];
  serve::SlaveAnswer a;
  std::string result;
  const int32_t s = doc_.Call(
      item, method, params.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), &result);
  if (s == ASGARD_OK) {
    a.result = nlohmann::json::parse(result, nullptr, false);
    a.ok = !a.result.is_discarded();
    if (!a.ok) a.error = "the medium answered '" + method + "' with text that is not JSON";
    return a;
  }
  a.error = item.message;
  // The slave is gone (not a refusal it answered): the next action restarts it.
  a.died = s == ASGARD_ERR_SLAVE || s == ASGARD_ERR_TIMEOUT || s == ASGARD_ERR_PROTOCOL;
  if (a.died) a.error += "; it restarts on the next action";
  return a;
}

serve::RenditionFrame RenditionOf(HostDocument& doc, Embedded& item, double t, bool handles) {
  serve::RenditionFrame f;
  // The document view may ask before any editor did: simulate first.
  if (!item.simulated && item.status.state != ASGARD_NODE_SCENE_ERROR) doc.Simulate(item);
  const Picture p =
      doc.Frame(item, ASGARD_DEVICE_SCREEN, item.width, item.height, t,
                handles ? static_cast<uint32_t>(ASGARD_RENDITION_HANDLES) : 0u, &f.live);
  f.status = item.message;
  if (!f.live && !p.empty() && p.rgba == item.poster.rgba)
    f.status += " · showing the poster frame";
  f.t0 = item.t0;
  f.t1 = item.t1;
  if (!p.empty()) f.png = EncodePng(p);
  return f;
}

serve::AttachHost AttachTo(HostDocument& doc) {
  return [&doc](const std::vector<size_t>& path, serve::Animation& a) {
    for (size_t i = 0; i < doc.items().size(); ++i) {
      Embedded& item = doc.items()[i];
      if (item.path != path || !item.medium || !item.medium->node_rpc()) continue;
      a.channel = std::make_shared<NodeChannel>(doc, i);
      a.rendition = [&doc, &item](double t, bool handles) {
        return RenditionOf(doc, item, t, handles);
      };
      return;
    }
  };
}

}  // namespace asgard::host
