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
 * The host reads the descriptors once, at load, and keeps the pointers.  It
 * creates instances freely, and not only to do work: `arbor` creates one
 * instance of every plugin of each kind a command takes options for, once per
 * command, only to read its parameter descriptions, and one of every
 * importer to probe a file.  Keep create_plugin cheap: allocate the instance
 * record and set defaults; open files, contexts and threads at the first
 * call that needs them.  An instance may be destroyed without any other
 * call.
 *
 * A library may hold several plugins (e.g. several simplifiers).  Each plugin
 * has one kind; an instance offers the interface of its kind plus optional
 * ones (parameters) through get_interface.
 *
 * Threading: the host never calls into one instance from two threads at once,
 * but it does not always call it from the same thread (the pipeline runs each
 * stage's work as a job on a thread of its own; an instance lives from one
 * job to the next).  Different instances, also of one plugin, run
 * concurrently (the pipeline's stages overlap; the legend and the depiction
 * use two instances of the depictor), unless the descriptor sets
 * ARBOR_PLUGIN_FLAG_SERIALIZE: then the host never runs two calls into any
 * instances of that plugin at the same time.  Tags in abi.h.
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
/* The host serialises the calls into all instances of this plugin (their
 * interfaces, parameters and destroy): for libraries that are not
 * thread-safe inside, such as a renderer driving VTK.  create_plugin is not
 * serialised.  Honoured since ABI 1.4 (documented since 1.0). */
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
 * its own destroy(); the host reads the fields but never writes them.  Every
 * function here and in the instance's interface tables is [instance]. */
struct arbor_plugin {
    uint32_t struct_size;
    uint32_t reserved0; /* 0; the padding before the pointers, named (ABI 1.3) */
    const arbor_plugin_descriptor *descriptor;
    void *plugin_data; /* private to the plugin */

    /* Release the instance.  Called exactly once, never during another call
     * into it, perhaps on another thread than the one that created it.
     * [instance] */
    void (*destroy)(arbor_plugin *plugin);

    /* The table of functions for interface_id (an ARBOR_INTERFACE_* string,
     * revision included), or NULL when the instance does not offer it.  The
     * table stays valid for the life of the instance, and the answer for an
     * id never changes.  [instance] [cheap] */
    const void *(*get_interface)(const arbor_plugin *plugin, const char *interface_id);

    /* Why the last failing call on this instance failed: one UTF-8 sentence
     * naming the input and the problem ("header of scan.nrrd: sizes 0 64 64:
     * every size must be positive").  "" after a successful call.  Valid until
     * the next call into the instance.  The host calls it right after the
     * failing call, on the same thread.  [instance] */
    const char *(*last_error)(const arbor_plugin *plugin);
};
#define ARBOR_MIN_SIZE_arbor_plugin ARBOR_SIZE_THROUGH(arbor_plugin, last_error) /* through ABI 1.0 */

typedef struct arbor_plugin_entry {
    uint32_t struct_size;
    arbor_version abi_version; /* set to ARBOR_ABI_VERSION_INIT */

    /* Called once after the library is loaded.  library_path is the file the
     * host loaded (to find data files next to it).  Anything but ARBOR_OK
     * makes the host refuse the library; log the reason through host->log.
     * `host` stays valid until deinit returns.  [main-thread]
     * [borrowed: library_path until return] */
    arbor_status (*init)(const arbor_host *host, const char *library_path);

    /* Called once before the library is unloaded, after every instance was
     * destroyed.  [main-thread] */
    void (*deinit)(void);

    /* Number of plugins in the library and their descriptors (index <
     * count).  Descriptors are static data valid until deinit: the host reads
     * them once, at load, and keeps the pointers.  [main-thread] */
    uint32_t (*plugin_count)(void);
    const arbor_plugin_descriptor *(*plugin_descriptor)(uint32_t index);

    /* Create an instance of the plugin with this id.  host stays valid for the
     * life of the instance.  On failure *out is set to NULL and the reason is
     * logged through host->log.  Called many times per command (see the top of
     * this file), from any thread, possibly while other instances of the
     * library work or are being created.  [thread-safe] [cheap]
     * [borrowed: plugin_id until return] */
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
