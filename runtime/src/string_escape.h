/* The language's string escapes (docs/language-reference.md §2), one table for the runtime's two
   readers of quoted strings: tools.c get_string (control tools, user code) and the engines'
   engine_values.c (start requests, scenario values). \n \t \r \b \f \0 are the control
   characters; a backslash before any other character stands for that character (\" \\ \x -> x).
   The language package reads them the same way (packages/language src/model/strings.ts). */
#ifndef CONTRACT_STRING_ESCAPE_H
#define CONTRACT_STRING_ESCAPE_H

/* The character `\e` stands for (e the character after the backslash, not '\0'). */
static inline char contract_string_escape(char e) {
    switch (e) {
    case 'n': return '\n';
    case 't': return '\t';
    case 'r': return '\r';
    case 'b': return '\b';
    case 'f': return '\f';
    case '0': return '\0';
    default: return e;
    }
}

#endif
