/*
 * The media plugin ABI of the document host (seed 6.1: what a medium must
 * provide — storage, subdocument nodes, presentations, renditions per output
 * device).
 *
 *   dochost ──dlopen("medium_<element>.so")──▶ asgard_medium_get_entry()
 *      │                                           │ abi_major/minor, struct_size,
 *      │                                           │ element name, get_interface(id)
 *      ├── ASGARD_IFACE_STORAGE       element body ⇄ medium text
 *      ├── ASGARD_IFACE_NODE          one node per subdocument (may run a slave process)
 *      ├── ASGARD_IFACE_PRESENTATION  the size the subdocument wants on the page
 *      ├── ASGARD_IFACE_RENDITION     one per (view, output device): RGBA frames
 *      └── ASGARD_IFACE_NODE_RPC      (1.1) the medium's own requests to a node's
 *                                     slave: a host's editor and its renditions
 *                                     share one slave and one state
 *
 * Rules: only C types cross; nothing throws across; every call that can fail
 * returns an asgard_status and fills an asgard_error (code + message).
 * Every struct starts with its size so either side can be older: a reader
 * uses only the fields inside the size it was given.  A host accepts a
 * plugin only when abi_major equals its own ASGARD_MEDIUM_ABI_MAJOR; minor
 * versions only add fields at the end or new interface ids.
 * Memory: asgard_bytes returned by a plugin belong to the host, which frees
 * them with the entry's free_bytes.  Frame pixels belong to the rendition
 * and stay valid until the next call on it.  Not thread-safe: a host calls a
 * node and its renditions from one thread at a time.
 */
#ifndef ASGARD_MEDIUM_ABI_H
#define ASGARD_MEDIUM_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define ASGARD_MEDIUM_ABI_MAJOR 1
#define ASGARD_MEDIUM_ABI_MINOR 1
/* The one exported symbol: const asgard_medium_entry* asgard_medium_get_entry(void); */
#define ASGARD_MEDIUM_ENTRY_SYMBOL "asgard_medium_get_entry"

typedef enum asgard_status {
  ASGARD_OK = 0,
  ASGARD_ERR_INVALID = 1,     /* bad argument or call out of order */
  ASGARD_ERR_SYNTAX = 2,      /* a storage body could not be decoded */
  ASGARD_ERR_SCENE = 3,       /* the medium text has errors, or the simulation failed */
  ASGARD_ERR_SLAVE = 4,       /* the slave process died or could not be started */
  ASGARD_ERR_TIMEOUT = 5,     /* the slave stopped answering (the watchdog killed it) */
  ASGARD_ERR_PROTOCOL = 6,    /* a malformed message from the slave */
  ASGARD_ERR_UNSUPPORTED = 7, /* not provided by this medium */
  ASGARD_ERR_INTERNAL = 8
} asgard_status;

typedef struct asgard_error {
  int32_t code; /* an asgard_status */
  char message[1024];
} asgard_error;

typedef struct asgard_bytes {
  char* data;
  size_t size;
} asgard_bytes;

enum {
  ASGARD_IFACE_STORAGE = 1,
  ASGARD_IFACE_NODE = 2,
  ASGARD_IFACE_PRESENTATION = 3,
  ASGARD_IFACE_RENDITION = 4,
  ASGARD_IFACE_NODE_RPC = 5 /* ABI 1.1 */
};

typedef struct asgard_medium_entry {
  uint32_t struct_size;
  uint32_t abi_major;
  uint32_t abi_minor;
  const char* element_name; /* the storage element the medium owns, e.g. "ASGARD" */
  const char* medium_name;  /* e.g. "Animation" */
  const char* description;
  /* The interface table for `id` (which starts with its own uint32_t
   * struct_size), or NULL when the medium does not provide it. */
  const void* (*get_interface)(uint32_t id);
  void (*free_bytes)(asgard_bytes* bytes);
} asgard_medium_entry;

typedef const asgard_medium_entry* (*asgard_medium_entry_fn)(void);

/* Storage (seed 6.2.1): the body is every byte between the element's start
 * and end tags, exactly as stored. */
typedef struct asgard_storage_v1 {
  uint32_t struct_size;
  int32_t (*decode)(const char* body, size_t size, asgard_bytes* text, asgard_error* error);
  int32_t (*encode)(const char* text, size_t size, asgard_bytes* body, asgard_error* error);
} asgard_storage_v1;

/* Subdocument nodes (seed 6.2.2). */
typedef struct asgard_node asgard_node;

typedef void (*asgard_progress_fn)(void* user, double fraction, const char* message);

typedef struct asgard_node_options {
  uint32_t struct_size;
  const char* slave_path; /* NULL: the medium finds its slave program itself */
  double timeout_seconds; /* watchdog: longest silence from the slave; <= 0: default */
  const char* name;       /* for messages, e.g. "memo.ens: animation 1" */
  /* Added later (read only when struct_size covers it): the slave's address
   * space in MiB; <= 0: the medium's default. */
  double slave_memory_mb;
} asgard_node_options;

typedef enum asgard_node_state {
  ASGARD_NODE_LOADED = 0,    /* text loaded, not simulated */
  ASGARD_NODE_SIMULATED = 1, /* frames can be drawn */
  ASGARD_NODE_SCENE_ERROR = 2,
  ASGARD_NODE_CRASHED = 3, /* the slave died; restart to continue */
  ASGARD_NODE_HUNG = 4,    /* the slave stopped answering and was killed */
  ASGARD_NODE_STOPPED = 5
} asgard_node_state;

typedef struct asgard_node_status {
  uint32_t struct_size;
  int32_t state; /* asgard_node_state */
  int32_t pid;   /* the slave's process id, 0 when there is none */
  int32_t bodies;
  double t0, t1, frame_rate; /* valid when simulated */
  char message[1024];        /* one line for a status caption */
} asgard_node_status;

typedef struct asgard_node_v1 {
  uint32_t struct_size;
  /* Starts the node (and its slave) with the medium text.  On
   * ASGARD_ERR_SCENE, and when the slave started but died or hung loading
   * the text (state CRASHED or HUNG; restart to continue), *node is set
   * though the status is not ASGARD_OK; the host destroys it as any other. */
  int32_t (*create)(const char* text, size_t size, const asgard_node_options* options,
                    asgard_node** node, asgard_error* error);
  /* Also destroys the node's renditions. */
  void (*destroy)(asgard_node* node);
  /* New text: re-evaluated and re-simulated. */
  int32_t (*update)(asgard_node* node, const char* text, size_t size, asgard_progress_fn progress,
                    void* user, asgard_error* error);
  int32_t (*simulate)(asgard_node* node, asgard_progress_fn progress, void* user,
                      asgard_error* error);
  /* A textual command for the medium (e.g. "handles on"); the reply is text. */
  int32_t (*command)(asgard_node* node, const char* line, asgard_bytes* reply, asgard_error* error);
  int32_t (*get_text)(asgard_node* node, asgard_bytes* text, asgard_error* error);
  void (*get_status)(asgard_node* node, asgard_node_status* status);
  /* A fresh slave with the node's text; renditions are reopened on use. */
  int32_t (*restart)(asgard_node* node, asgard_error* error);
} asgard_node_v1;

/* Presentations (seed 6.2.3): the size the subdocument would like, points. */
typedef struct asgard_presentation_v1 {
  uint32_t struct_size;
  int32_t (*desired_size)(asgard_node* node, int32_t* width, int32_t* height, asgard_error* error);
} asgard_presentation_v1;

/* Renditions: one per (view, output device). */
typedef enum asgard_device {
  ASGARD_DEVICE_SCREEN = 0,
  ASGARD_DEVICE_PAGE = 1, /* PDF and PNG pages */
  ASGARD_DEVICE_HTML = 2
} asgard_device;

enum { ASGARD_RENDITION_HANDLES = 1u, ASGARD_RENDITION_WIRE = 2u };

typedef struct asgard_rendition asgard_rendition;

typedef struct asgard_frame {
  uint32_t struct_size;
  int32_t width, height, stride; /* stride in bytes */
  const uint8_t* pixels;         /* RGBA, 8 bits each, rows from the top */
  double time;
} asgard_frame;

typedef struct asgard_rendition_v1 {
  uint32_t struct_size;
  int32_t (*create)(asgard_node* node, const char* view, int32_t device, int32_t width,
                    int32_t height, asgard_rendition** rendition, asgard_error* error);
  void (*destroy)(asgard_rendition* rendition);
  int32_t (*set_flags)(asgard_rendition* rendition, uint32_t flags, asgard_error* error);
  int32_t (*frame)(asgard_rendition* rendition, double time, asgard_frame* frame,
                   asgard_error* error);
} asgard_rendition_v1;

/* Added in ABI 1.1: a request in the medium's own protocol to a node's slave
 * (for the ASGARD medium: the editor's edit, create, delete, undo, redo,
 * scene_state, meshes, poses, load, simulate — asgard-core's JSON-RPC), so
 * that an editor the host serves and the node's renditions are one state: an
 * edit made here is what the renditions draw after the next simulate, and a
 * restart loads the edited text.  `params` is the text of a JSON object
 * (NULL or empty: {}).  On ASGARD_OK *result holds the answer's JSON text.
 * An error the slave answers is ASGARD_ERR_SCENE (scene or solver) or
 * ASGARD_ERR_INVALID with its message, and the slave goes on; a slave that
 * died, hung or broke the framing is ASGARD_ERR_SLAVE, _TIMEOUT or
 * _PROTOCOL and the node is CRASHED or HUNG (restart to continue).  Requests
 * that change the text change the node's text (get_text); `simulate` sets
 * its state and interval; the node's own requests (frames, renditions,
 * shutdown) are refused with ASGARD_ERR_INVALID. */
typedef struct asgard_node_rpc_v1 {
  uint32_t struct_size;
  int32_t (*call)(asgard_node* node, const char* method, const char* params, size_t params_size,
                  asgard_bytes* result, asgard_error* error);
} asgard_node_rpc_v1;

#ifdef __cplusplus
}
#endif

#endif /* ASGARD_MEDIUM_ABI_H */
