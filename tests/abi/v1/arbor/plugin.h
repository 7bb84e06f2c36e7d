/*
 * arbor/plugin.h - how a shared library presents its plugins to the host.
 *
 * A plugin library exports exactly one symbol, `arbor_entry`, of type
 * arbor_plugin_entry (use ARBOR_PLUGIN_ENTRY to define it).  The host:
 *
 *   1. checks entry.abi_version.major == ARBOR_ABI_VERSION_MAJOR,
 *   2. calls entry.init(host, path) once,
 *   3. enumerates descriptors with plugin_count / plugin_descriptor,
 *   4. creates instances with create_plugin(host, id) as it needs them,
 *   5. destroys all instances, then calls entry.deinit() once before unloading.
 *
 * A library may hold several plugins (e.g. several simplifiers).  Each plugin
 * has one kind; an instance offers the interface of its kind plus optional
 * ones (parameters) through get_interface.
 *
 * Threading: the host never calls into one instance from two threads at once.
 * Different instances may be called concurrently, unless the descriptor sets
 * ARBOR_PLUGIN_FLAG_SERIALIZE, in which case the host never runs two calls into
 * any instance of that plugin at the same time.
 */
#ifndef ARBOR_PLUGIN_H
#define ARBOR_PLUGIN_H

#include "abi.h"
#include "host.h"

/* Plugin kinds (the `kind` field of a descriptor) and the interface each
 * kind must offer. */
#define ARBOR_KIND_IMPORTER "importer"         /* ARBOR_INTERFACE_IMPORTER */
#define ARBOR_KIND_FILTER "filter"             /* ARBOR_INTERFACE_FILTER */
#define ARBOR_KIND_SIMPLIFIER "simplifier"     /* ARBOR_INTERFACE_SIMPLIFIER */
#define ARBOR_KIND_DEPICTOR "depictor"         /* ARBOR_INTERFACE_DEPICTOR */
#define ARBOR_KIND_TF_GENERATOR "tf-generator" /* ARBOR_INTERFACE_TF_GENERATOR */
#define ARBOR_KIND_RENDERER "renderer"         /* ARBOR_INTERFACE_RENDERER */

typedef uint32_t arbor_plugin_flags;
#define ARBOR_PLUGIN_FLAG_NONE 0u
/* The host serialises all calls into all instances of this plugin. */
#define ARBOR_PLUGIN_FLAG_SERIALIZE (1u << 0)
/* Shown as experimental in listings. */
#define ARBOR_PLUGIN_FLAG_EXPERIMENTAL (1u << 1)

typedef struct arbor_plugin_descriptor {
    uint32_t struct_size;
    arbor_plugin_flags flags;
    /* Reverse-DNS, lowercase, at least three dot-separated parts, e.g.
     * "org.arbor.simplifier.itri".  Never changes once released: sessions,
     * reports and scripts refer to plugins by id. */
    const char *id;
    const char *kind;        /* one of ARBOR_KIND_* */
    const char *name;        /* human-readable, e.g. "Importance triangle" */
    const char *version;     /* the plugin's own version, "MAJOR.MINOR.PATCH" */
    const char *vendor;      /* who made it */
    const char *description; /* one or two sentences */
    const char *url;         /* documentation, may be "" */
} arbor_plugin_descriptor;
#define ARBOR_MIN_SIZE_arbor_plugin_descriptor ARBOR_SIZE_THROUGH(arbor_plugin_descriptor, url) /* through ABI 1.0 */

typedef struct arbor_plugin arbor_plugin;

/* A plugin instance.  Allocated by the plugin in create_plugin and released by
 * its own destroy(); the host reads the fields but never writes them. */
struct arbor_plugin {
    uint32_t struct_size;
    uint32_t reserved0; /* 0; the padding before the pointers, named (ABI 1.3) */
    const arbor_plugin_descriptor *descriptor;
    void *plugin_data; /* private to the plugin */

    /* Release the instance.  Called exactly once. */
    void (*destroy)(arbor_plugin *plugin);

    /* The table of functions for interface_id (an ARBOR_INTERFACE_* string,
     * revision included), or NULL when the instance does not offer it.  The
     * table stays valid for the life of the instance. */
    const void *(*get_interface)(const arbor_plugin *plugin, const char *interface_id);

    /* Why the last failing call on this instance failed: one UTF-8 sentence
     * naming the input and the problem ("header of scan.nrrd: sizes 0 64 64:
     * every size must be positive").  "" after a successful call.  Valid until
     * the next call into the instance. */
    const char *(*last_error)(const arbor_plugin *plugin);
};
#define ARBOR_MIN_SIZE_arbor_plugin ARBOR_SIZE_THROUGH(arbor_plugin, last_error) /* through ABI 1.0 */

typedef struct arbor_plugin_entry {
    uint32_t struct_size;
    arbor_version abi_version; /* set to ARBOR_ABI_VERSION_INIT */

    /* Called once after the library is loaded.  library_path is the file the
     * host loaded (to find data files next to it).  Anything but ARBOR_OK
     * makes the host refuse the library; log the reason through host->log. */
    arbor_status (*init)(const arbor_host *host, const char *library_path);

    /* Called once before the library is unloaded, after every instance was
     * destroyed. */
    void (*deinit)(void);

    /* Number of plugins in the library and their descriptors (index <
     * count).  Descriptors are static data valid until deinit. */
    uint32_t (*plugin_count)(void);
    const arbor_plugin_descriptor *(*plugin_descriptor)(uint32_t index);

    /* Create an instance of the plugin with this id.  host stays valid for the
     * life of the instance.  On failure *out is set to NULL and the reason is
     * logged through host->log. */
    arbor_status (*create_plugin)(const arbor_host *host, const char *plugin_id,
                                  arbor_plugin **out);
} arbor_plugin_entry;
#define ARBOR_MIN_SIZE_arbor_plugin_entry ARBOR_SIZE_THROUGH(arbor_plugin_entry, create_plugin) /* through ABI 1.0 */

/* Name of the one exported symbol. */
#define ARBOR_ENTRY_SYMBOL "arbor_entry"

/* Define the entry symbol: ARBOR_PLUGIN_ENTRY = { sizeof(arbor_plugin_entry),
 * ARBOR_ABI_VERSION_INIT, my_init, ... }; */
#define ARBOR_PLUGIN_ENTRY ARBOR_EXTERN_C ARBOR_EXPORT const arbor_plugin_entry arbor_entry

#endif /* ARBOR_PLUGIN_H */
