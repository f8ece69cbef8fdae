/* tools.h: serialisation and parsing of primitive Cactal values. */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "tools.h"
#include "string_escape.h"

unsigned int extract_float(unsigned char *buffer, unsigned int offset, double value)
{
    memcpy(buffer + offset, &value, sizeof value);
    return sizeof value;
}

unsigned int extract_int(unsigned char *buffer, unsigned int offset, long value)
{
    memcpy(buffer + offset, &value, sizeof value);
    return sizeof value;
}

unsigned int extract_string(unsigned char *buffer, unsigned int offset, const char *value)
{
    size_t n = strnlen(value, CONTRACT_STRING_SIZE - 1);
    memcpy(buffer + offset, value, n);
    memset(buffer + offset + n, 0, CONTRACT_STRING_SIZE - n);
    return CONTRACT_STRING_SIZE;
}

unsigned int fill_float(double *value, unsigned int offset, unsigned char *buffer)
{
    memcpy(value, buffer + offset, sizeof *value);
    return sizeof *value;
}

unsigned int fill_int(long *value, unsigned int offset, unsigned char *buffer)
{
    memcpy(value, buffer + offset, sizeof *value);
    return sizeof *value;
}

unsigned int fill_string(char *value, unsigned int offset, unsigned char *buffer)
{
    memcpy(value, buffer + offset, CONTRACT_STRING_SIZE);
    value[CONTRACT_STRING_SIZE - 1] = '\0';
    return CONTRACT_STRING_SIZE;
}

static int skip_blanks(const char *s)
{
    int i = 0;
    while (s[i] && isspace((unsigned char)s[i])) i++;
    return i;
}

/* Length of a number literal at s (sign, digits, optional fraction and exponent), 0 if none.
 * *is_real tells whether it has a fraction or an exponent. */
static int scan_number(const char *s, int *is_real)
{
    int i = 0, digits = 0;
    *is_real = 0;
    if (s[i] == '-' || s[i] == '+') i++;
    while (isdigit((unsigned char)s[i])) { i++; digits++; }
    if (s[i] == '.') {
        *is_real = 1;
        i++;
        while (isdigit((unsigned char)s[i])) { i++; digits++; }
    }
    if (digits == 0) return 0;
    if (s[i] == 'e' || s[i] == 'E') {
        int j = i + 1;
        if (s[j] == '-' || s[j] == '+') j++;
        if (isdigit((unsigned char)s[j])) {
            while (isdigit((unsigned char)s[j])) j++;
            i = j;
            *is_real = 1;
        }
    }
    if (isalnum((unsigned char)s[i]) || s[i] == '_' || s[i] == '.') return 0; /* 1x, 1.2.3 */
    return i;
}

int get_float(double *value, char *description)
{
    if (!value || !description) return -1;
    int start = skip_blanks(description), is_real;
    int len = scan_number(description + start, &is_real);
    if (len == 0) return -1;
    char tmp[128];
    if (len >= (int)sizeof tmp) return -1;
    memcpy(tmp, description + start, (size_t)len);
    tmp[len] = '\0';
    errno = 0;
    double v = strtod(tmp, NULL);
    if (errno == ERANGE && (v > 1.0 || v < -1.0)) return -1;
    *value = v;
    return start + len;
}

int get_int(long *value, char *description)
{
    if (!value || !description) return -1;
    int start = skip_blanks(description), is_real;
    int len = scan_number(description + start, &is_real);
    if (len == 0 || is_real) return -1;
    char tmp[64];
    if (len >= (int)sizeof tmp) return -1;
    memcpy(tmp, description + start, (size_t)len);
    tmp[len] = '\0';
    errno = 0;
    long v = strtol(tmp, NULL, 10);
    if (errno == ERANGE) return -1;
    *value = v;
    return start + len;
}

int get_string(char *value, char *description)
{
    if (!value || !description) return -1;
    int i = skip_blanks(description);
    if (description[i] != '"') return -1;
    i++;
    char tmp[CONTRACT_STRING_SIZE];
    size_t n = 0;
    for (;;) {
        char c = description[i++];
        if (c == '\0') return -1; /* unterminated */
        if (c == '"') break;
        if (c == '\\') { /* the language's escapes (string_escape.h) */
            char e = description[i++];
            if (e == '\0') return -1; /* unterminated */
            c = contract_string_escape(e);
        }
        if (n >= CONTRACT_STRING_SIZE - 1) return -1; /* longer than 255 bytes */
        tmp[n++] = c;
    }
    memset(value, 0, CONTRACT_STRING_SIZE);
    memcpy(value, tmp, n);
    return i;
}

int increment_until_markerfound(char *description, char *symbol)
{
    if (!description || !symbol) return -1;
    int i = skip_blanks(description);
    if (description[i] != *symbol || *symbol == '\0') return -1;
    return i + 1;
}

int only_blanks_remain(const char *text)
{
    return text && text[skip_blanks(text)] == '\0';
}

/* ---- extension types ------------------------------------------------------------------ */

unsigned int extract_bool(unsigned char *buffer, unsigned int offset, bool value)
{
    buffer[offset] = value ? 1 : 0;
    return 1;
}

unsigned int fill_bool(bool *value, unsigned int offset, unsigned char *buffer)
{
    *value = buffer[offset] != 0;
    return 1;
}

static int ident_length(const char *s)
{
    int i = 0;
    if (!(isalpha((unsigned char)s[0]) || s[0] == '_')) return 0;
    while (isalnum((unsigned char)s[i]) || s[i] == '_') i++;
    return i;
}

int get_bool(bool *value, char *description)
{
    if (!value || !description) return -1;
    int start = skip_blanks(description);
    const char *p = description + start;
    int n = ident_length(p);
    if (n == 4 && strncmp(p, "true", 4) == 0) *value = true;
    else if (n == 5 && strncmp(p, "false", 5) == 0) *value = false;
    else if ((p[0] == '0' || p[0] == '1') && !isalnum((unsigned char)p[1]) && p[1] != '_' && p[1] != '.') {
        *value = p[0] == '1';
        n = 1;
    } else {
        return -1;
    }
    return start + n;
}

const char *enum_member_name(long value, const char *const *names, const long *values, int n)
{
    for (int i = 0; i < n; i++)
        if (values[i] == value) return names[i];
    return NULL;
}

int get_enum(long *value, char *description, const char *type_name, const char *const *names,
             const long *values, int n)
{
    if (!value || !description || !names || !values) return -1;
    int start = skip_blanks(description);
    const char *p = description + start;
    int len = ident_length(p);
    if (len > 0 && p[len] == '.' && type_name && (int)strlen(type_name) == len && strncmp(p, type_name, (size_t)len) == 0) {
        p += len + 1;
        len = ident_length(p);
    }
    if (len > 0) {
        for (int i = 0; i < n; i++)
            if ((int)strlen(names[i]) == len && strncmp(p, names[i], (size_t)len) == 0) {
                *value = values[i];
                return (int)(p + len - description);
            }
        return -1;
    }
    long v;
    int used = get_int(&v, description);
    if (used < 0 || !enum_member_name(v, names, values, n)) return -1;
    *value = v;
    return used;
}
