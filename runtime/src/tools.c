/* tools.h: serialisation and parsing of primitive Cactal values. */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "tools.h"

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
        if (c == '\\') {
            char e = description[i++];
            switch (e) {
            case 'n': c = '\n'; break;
            case 't': c = '\t'; break;
            case '"': case '\\': c = e; break;
            default: return -1;
            }
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
