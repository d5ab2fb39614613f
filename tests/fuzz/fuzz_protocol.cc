// asgard-core's request handler: any message body (after the length
// framing) is answered, never crashes the slave.  core_main.cc is compiled
// into this target with its main renamed; answers go to /dev/null.
#include <fcntl.h>

#include <cstdint>
#include <string>

#define main asgard_core_main
#include "core/app/core_main.cc"
#undef main

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const int null_fd = ::open("/dev/null", O_WRONLY);
  static Slave* slave = [] {
    ::setenv("ASGARD_CORE_FAULT", "", 1);
    return new Slave(-1, null_fd, nullptr, 0);
  }();
  const std::string body(reinterpret_cast<const char*>(data), size);
  if (!slave->Handle(body)) {  // shutdown: start afresh
    delete slave;
    slave = new Slave(-1, null_fd, nullptr, 0);
  }
  return 0;
}
