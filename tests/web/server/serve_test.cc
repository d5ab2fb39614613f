// The editor server's admission rules (web/server/server.h): loopback peers only,
// WebSocket upgrades only from our own origin and Host.
#include <gtest/gtest.h>

#include "web/server/server.h"

namespace asgard::serve {
namespace {

TEST(Serve, LoopbackPeersOnly) {
  EXPECT_TRUE(IsLoopbackPeer("127.0.0.1"));
  EXPECT_TRUE(IsLoopbackPeer("127.3.4.5"));
  EXPECT_TRUE(IsLoopbackPeer("::1"));
  EXPECT_TRUE(IsLoopbackPeer("::ffff:127.0.0.1"));
  EXPECT_FALSE(IsLoopbackPeer("192.168.1.20"));
  EXPECT_FALSE(IsLoopbackPeer("10.0.0.1"));
  EXPECT_FALSE(IsLoopbackPeer("::ffff:10.0.0.1"));
  EXPECT_FALSE(IsLoopbackPeer("2001:db8::1"));
  EXPECT_FALSE(IsLoopbackPeer("not an address"));
  EXPECT_FALSE(IsLoopbackPeer(""));
}

TEST(Serve, OwnOriginOnly) {
  EXPECT_TRUE(IsOwnOrigin("http://127.0.0.1:8080", "127.0.0.1:8080", 8080));
  EXPECT_TRUE(IsOwnOrigin("http://localhost:8080", "localhost:8080", 8080));
  EXPECT_TRUE(IsOwnOrigin("", "127.0.0.1:8080", 8080));  // a tool, not a browser
  EXPECT_FALSE(IsOwnOrigin("http://evil.example", "127.0.0.1:8080", 8080));
  EXPECT_FALSE(IsOwnOrigin("http://127.0.0.1:9090", "127.0.0.1:8080", 8080));
  EXPECT_FALSE(IsOwnOrigin("null", "127.0.0.1:8080", 8080));
  // DNS rebinding: a foreign name resolving to 127.0.0.1.
  EXPECT_FALSE(IsOwnOrigin("http://evil.example:8080", "evil.example:8080", 8080));
  EXPECT_FALSE(IsOwnOrigin("", "", 8080));
}

}  // namespace
}  // namespace asgard::serve
