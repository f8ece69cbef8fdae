/*
 * tools.h -- helpers used by the generated Shared<Type>.h files (report section 8.2) and by the
 * control tools: (de)serialisation of primitive values and parsing of their textual form.
 * Implemented in libmodule.a (src/tools.c). Audience: [GEN] generated code, [ENGINE] tools.
 *
 * Cactal -> C: float -> double, int -> long, string -> char[256] (CONTRACT_STRING_SIZE).
 *
 * Serialisation ("extract" = write into a buffer, "fill" = read back): values are written in
 * the host's byte order at buffer + offset; each function returns the number of bytes it wrote
 * or read, so that generated code can chain `size += extract_float(buffer, size, arg->i);`.
 * A string always takes CONTRACT_STRING_SIZE bytes (NUL-padded).
 *
 * Parsing (textual values as typed in control tools: `{1.0,{2,"a b"}}`): every get_* skips
 * leading white space, parses one value at the start of `description` and returns the number
 * of characters consumed, or -1 if there is no valid value there (nothing is written then).
 */
#ifndef CONTRACT_TOOLS_H
#define CONTRACT_TOOLS_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CONTRACT_STRING_SIZE 256

unsigned int extract_float(unsigned char *buffer, unsigned int offset, double value);
unsigned int extract_int(unsigned char *buffer, unsigned int offset, long value);
unsigned int extract_string(unsigned char *buffer, unsigned int offset, const char *value);

unsigned int fill_float(double *value, unsigned int offset, unsigned char *buffer);
unsigned int fill_int(long *value, unsigned int offset, unsigned char *buffer);
unsigned int fill_string(char *value, unsigned int offset, unsigned char *buffer);

/** Real or integer literal: `-1.5`, `2.`, `1e-3`, `3`. */
int get_float(double *value, char *description);
/** Integer literal (decimal, optional sign); a real such as `2.5` is refused. */
int get_int(long *value, char *description);
/** Double-quoted string `"..."` with escapes \" \\ \n \t; at most 255 bytes; `value` gets
 *  CONTRACT_STRING_SIZE bytes. */
int get_string(char *value, char *description);

/* ---- extension types (docs/language-reference.md): Cactal bool -> C bool, enumerations ---- */

/** A bool takes one byte (0 or 1). */
unsigned int extract_bool(unsigned char *buffer, unsigned int offset, bool value);
unsigned int fill_bool(bool *value, unsigned int offset, unsigned char *buffer);
/** `true` or `false` (also `1` / `0`). */
int get_bool(bool *value, char *description);
/** A member of an enumeration of `n` members (`names[i]` has C value `values[i]`): its name
 *  `AUTO`, the qualified `Mode.AUTO` (type_name "Mode"), or a number that is a member's value.
 *  Generated get_Mode: `long v; int r = get_enum(&v, d, "Mode", NAMES, VALUES, 3);
 *  if (r >= 0) *arg = (Mode)v; return r;` */
int get_enum(long *value, char *description, const char *type_name, const char *const *names,
             const long *values, int n);
/** The name of an enumeration value, or NULL when it is no member. */
const char *enum_member_name(long value, const char *const *names, const long *values, int n);

/** Skip white space up to and including the character *symbol. Returns the number of characters
 *  consumed, or -1 if another character (or the end of the text) comes first. */
int increment_until_markerfound(char *description, char *symbol);

/** 1 if only white space remains in `text` (used to reject trailing garbage), else 0. */
int only_blanks_remain(const char *text);

#ifdef __cplusplus
}
#endif
#endif /* CONTRACT_TOOLS_H */
