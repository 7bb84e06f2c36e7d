/* The C helper arbor/param_check.h, compiled as strict C99 (-std=c99
 * -pedantic -Wall -Wextra -Werror) and run: every status the ABI demands of
 * set(), values kept on refusal, text copied, parsing of the forms people
 * write.  Known answers written out by hand. */
#include <arbor/param_check.h>

#include <stdio.h>
#include <string.h>

static int failures = 0;

#define EXPECT(cond)                                                                                              \
    do {                                                                                                          \
        if (!(cond)) {                                                                                            \
            printf("%s:%d: expected %s\n", __FILE__, __LINE__, #cond);                                            \
            ++failures;                                                                                           \
        }                                                                                                         \
    } while (0)

static const char *const shapes[] = {"ramp", "hat", "box"};

enum { GAMMA, DIMS, CLEAR, SHAPE, LABEL, FILE_PATH, COUNT };

static const arbor_param_desc descs[COUNT] = {
    {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "gamma", .name = "Gamma",
     .group = "", .unit = "", .hint = "", .components = 1, .min_value = 0.5, .max_value = 4.0,
     .default_value = {2.0}, .default_text = ""},
    {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_INT, .id = "dims", .name = "Dims", .group = "",
     .unit = "", .hint = "", .components = 3, .flags = ARBOR_PARAM_FLAG_REQUIRED, .min_value = 1,
     .max_value = 4096, .default_value = {1, 1, 1}, .default_text = ""},
    {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_BOOL, .id = "clear", .name = "Clear",
     .group = "", .unit = "", .hint = "", .components = 1, .min_value = 0, .max_value = 1,
     .default_value = {1}, .default_text = ""},
    {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_CHOICE, .id = "shape", .name = "Shape",
     .group = "", .unit = "", .hint = "", .components = 1, .min_value = 0, .max_value = 2,
     .default_value = {1}, .choice_count = 3, .choices = shapes, .default_text = ""},
    {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_STRING, .id = "label", .name = "Label",
     .group = "", .unit = "", .hint = "", .components = 1, .default_text = "bone"},
    {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_PATH, .id = "file", .name = "File",
     .group = "", .unit = "", .hint = "", .components = 1, .default_text = ""},
};

static arbor_param_value number(arbor_param_type type, uint32_t components, double a, double b, double c)
{
    arbor_param_value v;
    memset(&v, 0, sizeof v);
    v.struct_size = sizeof v;
    v.type = type;
    v.components = components;
    v.number[0] = a;
    v.number[1] = b;
    v.number[2] = c;
    v.text = "";
    return v;
}

int main(void)
{
    arbor_param_slot slots[COUNT];
    arbor_param_value v, out;
    char msg[256];
    char text[32];

    /* Defaults. */
    arbor_param_reset(descs, COUNT, slots);
    EXPECT(slots[GAMMA].value.number[0] == 2.0);
    EXPECT(slots[DIMS].value.components == 3 && slots[DIMS].value.number[2] == 1.0);
    EXPECT(slots[SHAPE].value.number[0] == 1.0);
    EXPECT(strcmp(slots[LABEL].value.text, "bone") == 0);
    EXPECT(strcmp(slots[FILE_PATH].value.text, "") == 0);

    /* Find. */
    EXPECT(arbor_param_find(descs, COUNT, "shape") == SHAPE);
    EXPECT(arbor_param_find(descs, COUNT, "nope") == -1);
    EXPECT(arbor_param_find(descs, COUNT, NULL) == -1);

    /* FLOAT: inside, the bounds, outside, NaN, wrong type and count. */
    v = number(ARBOR_PARAM_FLOAT, 1, 3.5, 0, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_OK);
    EXPECT(slots[GAMMA].value.number[0] == 3.5);
    v.number[0] = 4.0;
    EXPECT(arbor_param_check(&descs[GAMMA], &v, msg, sizeof msg) == ARBOR_OK);
    v.number[0] = 0.5;
    EXPECT(arbor_param_check(&descs[GAMMA], &v, msg, sizeof msg) == ARBOR_OK);
    v.number[0] = 4.25;
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(strcmp(msg, "parameter 'gamma': 4.25 lies outside [0.5, 4]") == 0);
    EXPECT(slots[GAMMA].value.number[0] == 3.5); /* kept */
    v.number[0] = NAN;
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    v = number(ARBOR_PARAM_INT, 1, 2, 0, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    v = number(ARBOR_PARAM_FLOAT, 2, 2, 2, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", NULL, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    v = number(ARBOR_PARAM_FLOAT, 1, 2, 0, 0);
    v.struct_size = 4;
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);

    /* Success leaves the message empty, after a failure too. */
    v = number(ARBOR_PARAM_FLOAT, 1, 1.5, 0, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_OK);
    EXPECT(msg[0] == '\0');
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, NULL, 0) == ARBOR_OK);
    v.number[0] = 3.5;
    EXPECT(arbor_param_set(descs, COUNT, slots, "gamma", &v, msg, sizeof msg) == ARBOR_OK);

    /* Unknown and NULL ids. */
    v = number(ARBOR_PARAM_FLOAT, 1, 2, 0, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "nope", &v, msg, sizeof msg) == ARBOR_ERROR_NOT_FOUND);
    EXPECT(strcmp(msg, "parameter 'nope': no such parameter") == 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, NULL, &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);

    /* INT: whole numbers per component. */
    v = number(ARBOR_PARAM_INT, 3, 64, 64, 32);
    EXPECT(arbor_param_set(descs, COUNT, slots, "dims", &v, msg, sizeof msg) == ARBOR_OK);
    v.number[1] = 64.5;
    EXPECT(arbor_param_set(descs, COUNT, slots, "dims", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(strcmp(msg, "parameter 'dims': 64.5 is not a whole number") == 0);
    v.number[1] = 0;
    EXPECT(arbor_param_set(descs, COUNT, slots, "dims", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(slots[DIMS].value.number[0] == 64 && slots[DIMS].value.number[1] == 64 &&
           slots[DIMS].value.number[2] == 32);

    /* BOOL and CHOICE. */
    v = number(ARBOR_PARAM_BOOL, 1, 0, 0, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "clear", &v, msg, sizeof msg) == ARBOR_OK);
    v.number[0] = 2;
    EXPECT(arbor_param_set(descs, COUNT, slots, "clear", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(slots[CLEAR].value.number[0] == 0);
    v = number(ARBOR_PARAM_CHOICE, 1, 2, 0, 0);
    EXPECT(arbor_param_set(descs, COUNT, slots, "shape", &v, msg, sizeof msg) == ARBOR_OK);
    v.number[0] = 3;
    EXPECT(arbor_param_set(descs, COUNT, slots, "shape", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    v.number[0] = 0.5;
    EXPECT(arbor_param_set(descs, COUNT, slots, "shape", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    v.number[0] = -1;
    EXPECT(arbor_param_set(descs, COUNT, slots, "shape", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(slots[SHAPE].value.number[0] == 2);

    /* STRING: copied, NULL refused, too long refused, previous kept. */
    strcpy(text, "skull");
    v = number(ARBOR_PARAM_STRING, 1, 0, 0, 0);
    v.text = text;
    EXPECT(arbor_param_set(descs, COUNT, slots, "label", &v, msg, sizeof msg) == ARBOR_OK);
    strcpy(text, "xxxxx");
    EXPECT(strcmp(slots[LABEL].value.text, "skull") == 0);
    v.text = NULL;
    EXPECT(arbor_param_set(descs, COUNT, slots, "label", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    {
        static char long_text[ARBOR_PARAM_TEXT_MAX + 10];
        memset(long_text, 'a', sizeof long_text - 1);
        long_text[sizeof long_text - 1] = '\0';
        v.text = long_text;
        EXPECT(arbor_param_set(descs, COUNT, slots, "label", &v, msg, sizeof msg) == ARBOR_ERROR_TOO_LARGE);
    }
    EXPECT(strcmp(slots[LABEL].value.text, "skull") == 0);

    /* Get: the stored value; bad records refused. */
    memset(&out, 0, sizeof out);
    out.struct_size = sizeof out;
    EXPECT(arbor_param_get(descs, COUNT, slots, "dims", &out, msg, sizeof msg) == ARBOR_OK);
    EXPECT(out.type == ARBOR_PARAM_INT && out.components == 3 && out.number[2] == 32);
    EXPECT(arbor_param_get(descs, COUNT, slots, "label", &out, msg, sizeof msg) == ARBOR_OK);
    EXPECT(strcmp(out.text, "skull") == 0);
    EXPECT(arbor_param_get(descs, COUNT, slots, "nope", &out, msg, sizeof msg) == ARBOR_ERROR_NOT_FOUND);
    EXPECT(arbor_param_get(descs, COUNT, slots, "dims", NULL, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    out.struct_size = 4;
    EXPECT(arbor_param_get(descs, COUNT, slots, "dims", &out, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);

    /* Parse the forms people write. */
    EXPECT(arbor_param_parse(&descs[DIMS], "64,32,8", &v, msg, sizeof msg) == ARBOR_OK);
    EXPECT(v.components == 3 && v.number[0] == 64 && v.number[1] == 32 && v.number[2] == 8);
    EXPECT(arbor_param_parse(&descs[DIMS], "64,32", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT(arbor_param_parse(&descs[DIMS], "64,32,8,1", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT(arbor_param_parse(&descs[DIMS], "64,32,8.5", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(arbor_param_parse(&descs[GAMMA], "1.25", &v, msg, sizeof msg) == ARBOR_OK && v.number[0] == 1.25);
    EXPECT(arbor_param_parse(&descs[GAMMA], "nan", &v, msg, sizeof msg) == ARBOR_ERROR_OUT_OF_RANGE);
    EXPECT(arbor_param_parse(&descs[GAMMA], "abc", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT(arbor_param_parse(&descs[CLEAR], "true", &v, msg, sizeof msg) == ARBOR_OK && v.number[0] == 1);
    EXPECT(arbor_param_parse(&descs[CLEAR], "maybe", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT(arbor_param_parse(&descs[SHAPE], "box", &v, msg, sizeof msg) == ARBOR_OK && v.number[0] == 2);
    EXPECT(arbor_param_parse(&descs[SHAPE], "cone", &v, msg, sizeof msg) == ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT(strcmp(msg, "parameter 'shape': 'cone' is not one of its choices") == 0);
    EXPECT(arbor_param_parse(&descs[FILE_PATH], "/tmp/x", &v, msg, sizeof msg) == ARBOR_OK &&
           strcmp(v.text, "/tmp/x") == 0);
    /* A parsed value stores as it is. */
    EXPECT(arbor_param_parse(&descs[GAMMA], "0.75", &v, msg, sizeof msg) == ARBOR_OK);
    EXPECT(arbor_param_store(&descs[GAMMA], &slots[GAMMA], &v, msg, sizeof msg) == ARBOR_OK);
    EXPECT(slots[GAMMA].value.number[0] == 0.75);

    printf("param_check: %d failure(s)\n", failures);
    return failures == 0 ? 0 : 1;
}
