/*
 * pgm_stack.c - an Arbor importer in plain C: a folder of binary PGM images
 * (P5, one slice each, in file-name order) as one volume.
 *
 * Pixel (x, y) of the k-th file (names sorted bytewise) is voxel (x, y, k).
 * maxval up to 255 gives u8 voxels, up to 65535 u16 (PGM stores those big
 * endian).  A PGM says nothing about geometry or units, so parameters do:
 * `spacing` (mm), `value-offset` and `unit` (a CT exported as PGM with
 * stored = HU + 1024: value-offset -1024, unit HU).  Every slice must have
 * the first one's size and maxval, and hold exactly its pixels.
 *
 * Rules it follows (sdk/docs/contract.md): probe is cheap (it lists the
 * folder and reads two bytes of one file), read_header reads headers only
 * and allocates nothing in proportion to what a file claims, read_voxels
 * writes every voxel of the host's buffer through its strides, reports
 * progress per slice and stops when cancelled.  What read_header found (the
 * sorted file names) is kept for the read_voxels that follows on the same
 * path, in the instance.
 */
#define _POSIX_C_SOURCE 200809L
#include <arbor/arbor.h>
#include <arbor/param_check.h>

#include <dirent.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const arbor_plugin_descriptor descriptor = {
    .struct_size = sizeof(arbor_plugin_descriptor),
    .id = "org.arbor.example.pgm-stack",
    .kind = ARBOR_KIND_IMPORTER,
    .name = "PGM slice stack (example)",
    .version = "1.0.0",
    .vendor = "Arbor",
    .description = "A folder of binary PGM (P5) slices, in file-name order, as one volume. Example of an "
                   "importer in plain C.",
    .url = "",
};

enum { SPACING, VALUE_OFFSET, UNIT, PARAM_COUNT };

static const arbor_param_desc params[PARAM_COUNT] = {
    [SPACING] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "spacing",
                 .name = "Voxel spacing", .group = "Geometry", .unit = "mm",
                 .hint = "Distance between voxel centres along x, y and the slices", .components = 3,
                 .min_value = 1e-6, .max_value = 1e6, .default_value = {1, 1, 1}, .default_text = ""},
    [VALUE_OFFSET] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "value-offset",
                      .name = "Value offset", .group = "Values", .unit = "",
                      .hint = "physical = stored + offset (-1024 for a CT stored as HU + 1024)", .components = 1,
                      .min_value = -1e9, .max_value = 1e9, .default_value = {0}, .default_text = ""},
    [UNIT] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_STRING, .id = "unit",
              .name = "Unit", .group = "Values", .unit = "", .hint = "Unit of physical values (HU for CT)",
              .components = 1, .default_text = ""},
};

typedef struct pgm_header {
    int64_t width, height, maxval;
    long data_offset; /* bytes before the pixels */
} pgm_header;

typedef struct importer {
    arbor_plugin plugin;
    arbor_param_slot values[PARAM_COUNT];
    /* What read_header found, for read_voxels on the same path. */
    char *folder;
    char **files; /* full paths, sorted */
    size_t file_count;
    pgm_header header;
    char unit[64];
    char error[512];
} importer;

static importer *self_of(const arbor_plugin *p) { return p ? (importer *)p->plugin_data : NULL; }

/* Records the reason of a failure (printf-style) and returns its status. */
static arbor_status fail(importer *s, arbor_status status, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(s->error, sizeof s->error, format, args);
    va_end(args);
    return status;
}

static int is_pgm_name(const char *name)
{
    const size_t n = strlen(name);
    return n > 4 && name[0] != '.' && name[n - 4] == '.' && (name[n - 3] == 'p' || name[n - 3] == 'P') &&
           (name[n - 2] == 'g' || name[n - 2] == 'G') && (name[n - 1] == 'm' || name[n - 1] == 'M');
}

static int is_folder(const char *path)
{
    struct stat st;
    return path && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static void forget_files(importer *s)
{
    size_t i;
    for (i = 0; i < s->file_count; ++i)
        free(s->files[i]);
    free(s->files);
    free(s->folder);
    s->files = NULL;
    s->folder = NULL;
    s->file_count = 0;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The sorted PGM files of `folder` into s->files. */
static arbor_status list_files(importer *s, const char *folder)
{
    DIR *dir = opendir(folder);
    struct dirent *e;
    size_t capacity = 0;
    forget_files(s);
    if (!dir) {
        return fail(s, ARBOR_ERROR_IO, "%s: cannot open the folder (%s)", folder, strerror(errno));
    }
    while ((e = readdir(dir)) != NULL) {
        char *path;
        if (!is_pgm_name(e->d_name))
            continue;
        if (s->file_count == capacity) {
            char **grown = (char **)realloc(s->files, (capacity ? 2 * capacity : 64) * sizeof *grown);
            if (!grown) {
                closedir(dir);
                return fail(s, ARBOR_ERROR_OUT_OF_MEMORY, "out of memory listing the folder");
            }
            s->files = grown;
            capacity = capacity ? 2 * capacity : 64;
        }
        path = (char *)malloc(strlen(folder) + strlen(e->d_name) + 2);
        if (!path) {
            closedir(dir);
            return fail(s, ARBOR_ERROR_OUT_OF_MEMORY, "out of memory listing the folder");
        }
        sprintf(path, "%s/%s", folder, e->d_name);
        s->files[s->file_count++] = path;
    }
    closedir(dir);
    if (s->file_count == 0) {
        return fail(s, ARBOR_ERROR_FORMAT, "%s: no .pgm files in the folder", folder);
    }
    qsort(s->files, s->file_count, sizeof *s->files, compare_names);
    s->folder = (char *)malloc(strlen(folder) + 1);
    if (!s->folder)
        return fail(s, ARBOR_ERROR_OUT_OF_MEMORY, "out of memory");
    strcpy(s->folder, folder);
    return ARBOR_OK;
}

/* One header field: skips whitespace and comments, reads a decimal number. */
static int read_number(FILE *f, int64_t *out)
{
    int c = fgetc(f);
    int64_t n = 0;
    int digits = 0;
    for (;;) {
        while (c == ' ' || c == '\t' || c == '\n' || c == '\r')
            c = fgetc(f);
        if (c != '#')
            break;
        while (c != '\n' && c != EOF)
            c = fgetc(f);
    }
    while (c >= '0' && c <= '9') {
        if (n > 100000000)
            return 0; /* absurdly large */
        n = 10 * n + (c - '0');
        ++digits;
        c = fgetc(f);
    }
    /* Exactly one whitespace byte ends the last field; the others' too. */
    if (!digits || !(c == ' ' || c == '\t' || c == '\n' || c == '\r'))
        return 0;
    *out = n;
    return 1;
}

/* The header of one file, checked against its size. */
static arbor_status read_pgm_header(importer *s, const char *path, pgm_header *h)
{
    FILE *f = fopen(path, "rb");
    long end;
    int64_t bytes;
    if (!f) {
        return fail(s, ARBOR_ERROR_IO, "%s: cannot open (%s)", path, strerror(errno));
    }
    if (fgetc(f) != 'P' || fgetc(f) != '5' || !read_number(f, &h->width) || !read_number(f, &h->height) ||
        !read_number(f, &h->maxval)) {
        fclose(f);
        return fail(s, ARBOR_ERROR_FORMAT, "%s: not a binary PGM (P5) header", path);
    }
    h->data_offset = ftell(f);
    fseek(f, 0, SEEK_END);
    end = ftell(f);
    fclose(f);
    if (h->width < 1 || h->height < 1 || h->maxval < 1 || h->maxval > 65535) {
        return fail(s, ARBOR_ERROR_FORMAT, "%s: size %lldx%lld or maxval %lld out of range", path,
                 (long long)h->width, (long long)h->height, (long long)h->maxval);
    }
    bytes = h->width * h->height * (h->maxval > 255 ? 2 : 1);
    if ((int64_t)end - h->data_offset != bytes) {
        return fail(s, ARBOR_ERROR_FORMAT, "%s: holds %lld bytes of pixels, its header says %lldx%lld = %lld", path,
                 (long long)((int64_t)end - h->data_offset), (long long)h->width, (long long)h->height,
                 (long long)bytes);
    }
    return ARBOR_OK;
}

static arbor_status probe(arbor_plugin *plugin, const char *path, const uint8_t *head, uint64_t head_size,
                          int32_t *confidence)
{
    importer *s = self_of(plugin);
    DIR *dir;
    struct dirent *e;
    if (!s)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    s->error[0] = '\0';
    if (!path || !confidence || (!head && head_size > 0))
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "probe: NULL path, confidence or head");
    *confidence = 0;
    if (!is_folder(path) || !(dir = opendir(path)))
        return ARBOR_OK; /* only folders */
    while ((e = readdir(dir)) != NULL)
        if (is_pgm_name(e->d_name)) {
            char file[4096];
            FILE *f;
            snprintf(file, sizeof file, "%s/%s", path, e->d_name);
            if ((f = fopen(file, "rb")) != NULL) {
                const int a = fgetc(f), b = fgetc(f);
                fclose(f);
                *confidence = a == 'P' && b == '5' ? 90 : 0;
            }
            break;
        }
    closedir(dir);
    return ARBOR_OK;
}

static arbor_status read_header(arbor_plugin *plugin, const char *path, arbor_task *task, arbor_volume *out)
{
    importer *s = self_of(plugin);
    arbor_status status;
    size_t k;
    int a;
    if (!s)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    s->error[0] = '\0';
    if (!path || !out || out->struct_size < ARBOR_MIN_SIZE(arbor_volume))
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "read_header: NULL path or volume, or volume too small");
    if (!is_folder(path)) {
        return fail(s, ARBOR_ERROR_UNSUPPORTED, "%s: not a folder (this importer reads folders of PGM slices)", path);
    }
    if ((status = list_files(s, path)) != ARBOR_OK)
        return status;
    if ((status = read_pgm_header(s, s->files[0], &s->header)) != ARBOR_OK)
        return status;
    for (k = 1; k < s->file_count; ++k) {
        pgm_header h;
        if (task && task->cancelled(task))
            return fail(s, ARBOR_ERROR_CANCELLED, "cancelled");
        if ((status = read_pgm_header(s, s->files[k], &h)) != ARBOR_OK)
            return status;
        if (h.width != s->header.width || h.height != s->header.height ||
            (h.maxval > 255) != (s->header.maxval > 255)) {
            return fail(s, ARBOR_ERROR_FORMAT, "%s: %lldx%lld, maxval %lld, differs from the first slice's", s->files[k],
                     (long long)h.width, (long long)h.height, (long long)h.maxval);
        }
    }
    out->voxel_type = s->header.maxval > 255 ? ARBOR_VOXEL_U16 : ARBOR_VOXEL_U8;
    out->dims[0] = s->header.width;
    out->dims[1] = s->header.height;
    out->dims[2] = (int64_t)s->file_count;
    for (a = 0; a < 3; ++a) {
        out->spacing[a] = s->values[SPACING].value.number[a];
        out->origin[a] = 0.0;
    }
    memset(out->direction, 0, sizeof out->direction);
    out->direction[0] = out->direction[4] = out->direction[8] = 1.0;
    out->value_scale = 1.0;
    out->value_offset = s->values[VALUE_OFFSET].value.number[0];
    snprintf(s->unit, sizeof s->unit, "%s", s->values[UNIT].value.text);
    out->value_unit = s->unit; /* valid until the next call into the instance */
    return ARBOR_OK;
}

static arbor_status read_voxels(arbor_plugin *plugin, const char *path, arbor_task *task, arbor_volume *volume)
{
    importer *s = self_of(plugin);
    arbor_status status;
    unsigned char *row;
    int64_t x, y;
    size_t k, bytes_per;
    if (!s)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    s->error[0] = '\0';
    if (!path || !volume || volume->struct_size < ARBOR_MIN_SIZE(arbor_volume) || !volume->voxels)
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "read_voxels: NULL path, volume or voxels");
    if (!s->folder || strcmp(s->folder, path) != 0) {
        /* Not the path read_header saw last: look again. */
        arbor_volume header = *volume;
        if ((status = read_header(plugin, path, task, &header)) != ARBOR_OK)
            return status;
    }
    bytes_per = s->header.maxval > 255 ? 2 : 1;
    if (volume->dims[0] != s->header.width || volume->dims[1] != s->header.height ||
        volume->dims[2] != (int64_t)s->file_count ||
        volume->voxel_type != (bytes_per == 2 ? ARBOR_VOXEL_U16 : ARBOR_VOXEL_U8))
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "read_voxels: the volume is not the header's");
    row = (unsigned char *)malloc((size_t)s->header.width * bytes_per);
    if (!row)
        return fail(s, ARBOR_ERROR_OUT_OF_MEMORY, "out of memory for one row");
    for (k = 0; k < s->file_count; ++k) {
        FILE *f;
        if (task && task->progress(task, (double)k / (double)s->file_count, "reading slices")) {
            free(row);
            return fail(s, ARBOR_ERROR_CANCELLED, "cancelled");
        }
        f = fopen(s->files[k], "rb");
        if (!f || fseek(f, s->header.data_offset, SEEK_SET) != 0) {
            if (f)
                fclose(f);
            free(row);
            return fail(s, ARBOR_ERROR_IO, "%s: cannot read (%s)", s->files[k], strerror(errno));
        }
        for (y = 0; y < s->header.height; ++y) {
            unsigned char *dst = (unsigned char *)volume->voxels + y * volume->strides[1] + (int64_t)k * volume->strides[2];
            if (fread(row, bytes_per, (size_t)s->header.width, f) != (size_t)s->header.width) {
                fclose(f);
                free(row);
                return fail(s, ARBOR_ERROR_FORMAT, "%s: ends before row %lld", s->files[k], (long long)y);
            }
            for (x = 0; x < s->header.width; ++x) {
                if (bytes_per == 1) {
                    dst[x * volume->strides[0]] = row[x];
                } else {
                    const uint16_t v = (uint16_t)((row[2 * x] << 8) | row[2 * x + 1]); /* big endian */
                    memcpy(dst + x * volume->strides[0], &v, sizeof v);
                }
            }
        }
        fclose(f);
    }
    free(row);
    if (task)
        task->progress(task, 1.0, "reading slices");
    return ARBOR_OK;
}

static const arbor_importer_v1 importer_interface = {
    .suffixes = "/", .probe = probe, .read_header = read_header, .read_voxels = read_voxels};

static uint32_t param_count(const arbor_plugin *plugin)
{
    (void)plugin;
    return PARAM_COUNT;
}

static const arbor_param_desc *param_describe(const arbor_plugin *plugin, uint32_t index)
{
    (void)plugin;
    return index < PARAM_COUNT ? &params[index] : NULL;
}

static arbor_status param_get(const arbor_plugin *plugin, const char *id, arbor_param_value *out)
{
    importer *s = self_of(plugin);
    return s ? arbor_param_get(params, PARAM_COUNT, s->values, id, out, s->error, sizeof s->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static arbor_status param_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    importer *s = self_of(plugin);
    return s ? arbor_param_set(params, PARAM_COUNT, s->values, id, value, s->error, sizeof s->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static const arbor_params_v1 params_interface = {
    .count = param_count, .describe = param_describe, .get = param_get, .set = param_set};

static void destroy(arbor_plugin *plugin)
{
    importer *s = self_of(plugin);
    if (s)
        forget_files(s);
    free(s);
}

static const void *get_interface(const arbor_plugin *plugin, const char *id)
{
    (void)plugin;
    if (id && strcmp(id, ARBOR_INTERFACE_IMPORTER) == 0)
        return &importer_interface;
    if (id && strcmp(id, ARBOR_INTERFACE_PARAMS) == 0)
        return &params_interface;
    return NULL;
}

static const char *last_error(const arbor_plugin *plugin)
{
    importer *s = self_of(plugin);
    return s ? s->error : "not an instance";
}

static arbor_status init(const arbor_host *host, const char *library_path)
{
    (void)host;
    (void)library_path;
    return ARBOR_OK;
}

static void deinit(void) {}

static uint32_t plugin_count(void) { return 1; }

static const arbor_plugin_descriptor *plugin_descriptor(uint32_t index)
{
    return index == 0 ? &descriptor : NULL;
}

static arbor_status create_plugin(const arbor_host *host, const char *id, arbor_plugin **out)
{
    importer *s;
    (void)host;
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!id)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    if (strcmp(id, descriptor.id) != 0)
        return ARBOR_ERROR_NOT_FOUND;
    s = (importer *)calloc(1, sizeof *s);
    if (!s)
        return ARBOR_ERROR_OUT_OF_MEMORY;
    s->plugin.struct_size = sizeof(arbor_plugin);
    s->plugin.descriptor = &descriptor;
    s->plugin.plugin_data = s;
    s->plugin.destroy = destroy;
    s->plugin.get_interface = get_interface;
    s->plugin.last_error = last_error;
    arbor_param_reset(params, PARAM_COUNT, s->values);
    *out = &s->plugin;
    return ARBOR_OK;
}

ARBOR_PLUGIN_ENTRY = {
    .struct_size = sizeof(arbor_plugin_entry),
    .abi_version = ARBOR_ABI_VERSION_INIT,
    .init = init,
    .deinit = deinit,
    .plugin_count = plugin_count,
    .plugin_descriptor = plugin_descriptor,
    .create_plugin = create_plugin,
};
