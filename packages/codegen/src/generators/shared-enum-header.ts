import { expandToNode, toString } from 'langium/generate';
import type { EnumDecl } from '../model/architecture.js';
import { cEnumMember } from './c/c-syntax.js';

/**
 * `common/Shared<Enum>.h` of an enumeration (an extension of the report): the C enum, members
 * prefixed by the enumeration's name (`Mode_AUTO`: two enumerations may share member names), and
 * the same functions as a datatype's header (serialize_/deserialize_/eq_/.../get_/print_), so that
 * datatypes, ports and control tools use an enumeration like any other type. Values are written
 * and read by member name (`AUTO`; `Mode.AUTO` and the number are accepted too).
 */
export function sharedEnumPath(name: string): string {
    return `generated/architecture/common/Shared${name}.h`;
}

export function generateSharedEnumHeader(e: EnumDecl): string {
    const E = e.name;
    const guard = `SHARED_${E.toUpperCase()}_H`;
    const members = e.members.map((m, i) => `${cEnumMember(E, m)} = ${i}`).join(', ');
    const names = e.members.map((m) => `"${m}"`).join(', ');
    const cmp = (fn: string, op: string) => `static inline int ${fn}_${E}(${E} * arg1, ${E} * arg2){ return *arg1 ${op} *arg2; }`;
    const node = expandToNode`
        #ifndef ${guard}
        #define ${guard}
        #include <stdio.h>
        #include <string.h>
        #include "tools.h"

        /* enum ${E} { ${e.members.join(', ')} } */
        typedef enum ${E} { ${members} } ${E};

        static inline unsigned int serialize_${E}(${E} * arg, unsigned char * buffer){ return extract_int(buffer, 0, (long)*arg); }
        static inline unsigned int deserialize_${E}(${E} * arg, unsigned char* buffer){
            long value = 0;
            unsigned int size = fill_int(&value, 0, buffer);
            if (value >= 0 && value < ${e.members.length}) *arg = (${E})value;
            return size;
        }
        ${cmp('eq', '==')}
        ${cmp('diff', '!=')}
        ${cmp('inf', '<')}
        ${cmp('sup', '>')}
        ${cmp('infeq', '<=')}
        ${cmp('supeq', '>=')}
        static inline void set_${E}(${E} * arg1, ${E} * arg2){ *arg1 = *arg2; }

        /* parses a member name (AUTO or ${E}.AUTO) or its number; returns the number of characters
           read, or -1 (then *arg is unchanged) */
        static inline int get_${E}(${E} * arg, char* description){
            static const char *const names[${e.members.length}] = { ${names} };
            int i = 0;
            if (arg == NULL || description == NULL) return -1;
            while (description[i] == ' ' || description[i] == '\\t' || description[i] == '\\n' || description[i] == '\\r') i++;
            if (strncmp(&description[i], "${E}.", ${E.length + 1}) == 0) i += ${E.length + 1};
            for (unsigned int m = 0; m < ${e.members.length}; m++) {
                size_t n = strlen(names[m]);
                char next = description[i + (int)n];
                if (strncmp(&description[i], names[m], n) == 0 && !(next == '_' || (next >= '0' && next <= '9') || (next >= 'a' && next <= 'z') || (next >= 'A' && next <= 'Z'))) {
                    *arg = (${E})m;
                    return i + (int)n;
                }
            }
            long value = 0;
            int res = get_int(&value, &description[i]);
            if (res == -1 || value < 0 || value >= ${e.members.length}) return -1;
            *arg = (${E})value;
            return i + res;
        }

        static inline void print_${E}(${E} * arg){
            static const char *const names[${e.members.length}] = { ${names} };
            if ((int)*arg >= 0 && (int)*arg < ${e.members.length}) printf("%s", names[*arg]);
            else printf("%d", (int)*arg);
        }

        #endif
    `;
    return toString(node) + '\n';
}
