/* A medium plugin built for a future ABI major version: the host must refuse it. */
#include "asgard/medium_abi.h"

static const void* GetInterface(uint32_t id) {
  (void)id;
  return 0;
}

static const asgard_medium_entry kEntry = {sizeof(asgard_medium_entry),
                                           ASGARD_MEDIUM_ABI_MAJOR + 1,
                                           3,
                                           "FUTURE",
                                           "Future",
                                           "from another ABI",
                                           GetInterface,
                                           0};

__attribute__((visibility("default"))) const asgard_medium_entry* asgard_medium_get_entry(void) {
  return &kEntry;
}
