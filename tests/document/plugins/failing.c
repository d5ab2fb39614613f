/* A medium plugin whose every call fails with an error code and a message:
 * the host must report the messages and go on. */
#include <stdio.h>
#include <string.h>

#include "asgard/medium_abi.h"

static int32_t Fail(asgard_error* e, int32_t code, const char* message) {
  if (e) {
    e->code = code;
    snprintf(e->message, sizeof e->message, "%s", message);
  }
  return code;
}

static int32_t Decode(const char* body, size_t size, asgard_bytes* text, asgard_error* e) {
  (void)body, (void)text;
  /* Bodies that start with "ok" decode; everything else is refused. */
  if (size >= 3 && memcmp(body, "{ok", 3) == 0) {
    static char ok[] = "ok";
    text->data = ok;
    text->size = 2;
    return ASGARD_OK;
  }
  return Fail(e, ASGARD_ERR_SYNTAX, "failing medium: this body is refused on purpose");
}
static int32_t Encode(const char* t, size_t n, asgard_bytes* body, asgard_error* e) {
  (void)t, (void)n, (void)body;
  return Fail(e, ASGARD_ERR_UNSUPPORTED, "failing medium: cannot encode");
}
static int32_t Create(const char* t, size_t n, const asgard_node_options* o, asgard_node** node,
                      asgard_error* e) {
  (void)t, (void)n, (void)o;
  *node = 0;
  return Fail(e, ASGARD_ERR_SLAVE, "failing medium: no node today");
}
static void Destroy(asgard_node* n) { (void)n; }
static int32_t Update(asgard_node* n, const char* t, size_t s, asgard_progress_fn p, void* u,
                      asgard_error* e) {
  (void)n, (void)t, (void)s, (void)p, (void)u;
  return Fail(e, ASGARD_ERR_INTERNAL, "failing medium: update");
}
static int32_t Simulate(asgard_node* n, asgard_progress_fn p, void* u, asgard_error* e) {
  (void)n, (void)p, (void)u;
  return Fail(e, ASGARD_ERR_INTERNAL, "failing medium: simulate");
}
static int32_t Command(asgard_node* n, const char* l, asgard_bytes* r, asgard_error* e) {
  (void)n, (void)l, (void)r;
  return Fail(e, ASGARD_ERR_INTERNAL, "failing medium: command");
}
static int32_t Text(asgard_node* n, asgard_bytes* t, asgard_error* e) {
  (void)n, (void)t;
  return Fail(e, ASGARD_ERR_INTERNAL, "failing medium: text");
}
static void Status(asgard_node* n, asgard_node_status* s) { (void)n, (void)s; }
static int32_t Restart(asgard_node* n, asgard_error* e) {
  (void)n;
  return Fail(e, ASGARD_ERR_INTERNAL, "failing medium: restart");
}
static void NoFree(asgard_bytes* b) { (void)b; }

static const asgard_storage_v1 kStorage = {sizeof(asgard_storage_v1), Decode, Encode};
static const asgard_node_v1 kNode = {
    sizeof(asgard_node_v1), Create, Destroy, Update, Simulate, Command, Text, Status, Restart};

static const void* GetInterface(uint32_t id) {
  if (id == ASGARD_IFACE_STORAGE) return &kStorage;
  if (id == ASGARD_IFACE_NODE) return &kNode;
  return 0;
}

static const asgard_medium_entry kEntry = {sizeof(asgard_medium_entry),
                                           ASGARD_MEDIUM_ABI_MAJOR,
                                           ASGARD_MEDIUM_ABI_MINOR,
                                           "FAILING",
                                           "Failing",
                                           "fails on purpose",
                                           GetInterface,
                                           NoFree};

__attribute__((visibility("default"))) const asgard_medium_entry* asgard_medium_get_entry(void) {
  return &kEntry;
}
