import { expandToNode, joinToNode, toString } from 'langium/generate';
import type { Datatype, Field } from '../model/architecture.js';
import { cDeclaration } from './c/c-syntax.js';
import { blockRegion } from './c/regions.js';
import { architecturePath } from '@contract-studio/conventions';

/** `common/Shared<Type>.h`: the struct and its functions (report §5.1, §8.2), all `static inline`. */
export function sharedTypePath(name: string): string {
    return architecturePath(`common/Shared${name}.h`);
}

function kindOf(f: Field): 'long' | 'double' | 'string' | 'struct' {
    if ('datatype' in f.type) return 'struct';
    return f.type.primitive === 'int' ? 'long' : f.type.primitive === 'float' ? 'double' : 'string';
}
const prim = { long: 'int', double: 'float', string: 'string' } as const;

function serializeField(f: Field): string {
    const k = kindOf(f);
    if (k === 'struct') return `size += serialize_${(f.type as { datatype: string }).datatype}(&arg->${f.name}, &buffer[size]);`;
    return `size += extract_${prim[k]}(buffer, size, arg->${f.name});`;
}

function deserializeField(f: Field): string {
    const k = kindOf(f);
    if (k === 'struct') return `size += deserialize_${(f.type as { datatype: string }).datatype}(&arg->${f.name}, &buffer[size]);`;
    if (k === 'string') return `size += fill_string(arg->${f.name}, size, buffer);`;
    return `size += fill_${prim[k]}(&arg->${f.name}, size, buffer);`;
}

function setField(f: Field): string {
    const k = kindOf(f);
    if (k === 'struct') return `set_${(f.type as { datatype: string }).datatype}(&arg1->${f.name}, &arg2->${f.name});`;
    if (k === 'string') return `memmove(arg1->${f.name}, arg2->${f.name}, sizeof(arg1->${f.name}));`;
    return `arg1->${f.name}=arg2->${f.name};`;
}

function getField(f: Field): string {
    const k = kindOf(f);
    if (k === 'struct') return `get_${(f.type as { datatype: string }).datatype}(&tmp.${f.name}, &description[sizeread])`;
    if (k === 'string') return `get_string(tmp.${f.name}, &description[sizeread])`;
    return `get_${prim[k]}(&tmp.${f.name}, &description[sizeread])`;
}

function printField(f: Field): string {
    switch (kindOf(f)) {
        case 'struct':
            return `printf("%s : ", "${f.name}"); print_${(f.type as { datatype: string }).datatype}(&arg->${f.name}); printf(" ; ");`;
        case 'string':
            return `printf("%s : %s ; ", "${f.name}", arg->${f.name});`;
        case 'long':
            return `printf("%s : %ld ; ", "${f.name}", arg->${f.name});`;
        case 'double':
            return `printf("%s : %lf ; ", "${f.name}", arg->${f.name});`;
    }
}

/** The C truth value of `arg1->x OP arg2->x` for every kind of field; OP one of == < >. */
function compareField(f: Field, op: '==' | '<' | '>'): string {
    const fn = { '==': 'eq', '<': 'inf', '>': 'sup' }[op];
    switch (kindOf(f)) {
        case 'struct':
            return `${fn}_${(f.type as { datatype: string }).datatype}(&arg1->${f.name}, &arg2->${f.name})`;
        case 'string':
            return `strcmp(arg1->${f.name}, arg2->${f.name}) ${op} 0`;
        default:
            return `arg1->${f.name} ${op} arg2->${f.name}`;
    }
}

/** Default comparison: true when the relation holds for every field (report §8.2). */
function comparisonBody(fields: Field[], op: '==' | '<' | '>'): string {
    if (fields.length === 0) return `(void)arg1; (void)arg2;\nreturn ${op === '==' ? 1 : 0};\n`;
    return fields.map((f) => `if (!(${compareField(f, op)})) return 0;\n`).join('') + 'return 1;\n';
}

export function generateSharedTypeHeader(type: Datatype): string {
    const T = type.name;
    const guard = `SHARED_${T.toUpperCase()}_H`;
    const deps = [...new Set(type.fields.flatMap((f) => ('datatype' in f.type ? [f.type.datatype] : [])))];
    const members = type.fields.length > 0 ? type.fields.map((f) => `${cDeclaration(f.type, f.name)};`) : ['char _empty; /* a C struct needs one member */'];
    const getFields = type.fields.map((f, i) => expandToNode`
        if ((res = ${getField(f)}) == -1) return -1;
        sizeread += res;
        symbol = '${i === type.fields.length - 1 ? '}' : ','}';
        if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
        sizeread += res;
    `);
    const node = expandToNode`
        #ifndef ${guard}
        #define ${guard}
        #include <stdio.h>
        #include <string.h>
        #include "tools.h"
        ${joinToNode(deps, (d) => `#include "Shared${d}.h"`, { appendNewLineIfNotEmpty: true })}

        //from here you can make new inclusions and definitions
        ${blockRegion(`protect_additional_import_${T}`, '//TODO')}

        typedef struct ${T}{
            ${joinToNode(members, (m) => m, { appendNewLineIfNotEmpty: true })}
        } ${T};

        static inline unsigned int serialize_${T}(${T} * arg, unsigned char * buffer);
        static inline unsigned int deserialize_${T}(${T} * arg, unsigned char* buffer);
        static inline int diff_${T}(${T} * arg1, ${T} * arg2);
        static inline int eq_${T}(${T} * arg1, ${T} * arg2);
        static inline int inf_${T}(${T} * arg1, ${T} * arg2);
        static inline int sup_${T}(${T} * arg1, ${T} * arg2);
        static inline int infeq_${T}(${T} * arg1, ${T} * arg2);
        static inline int supeq_${T}(${T} * arg1, ${T} * arg2);
        static inline void set_${T}(${T} * arg1, ${T} * arg2);
        static inline int get_${T}(${T} * arg, char* description);
        static inline void print_${T}(${T} * arg);

        //from here you can declare new functions
        ${blockRegion(`protect_additional_decl_${T}`, '//TODO')}

        static inline unsigned int serialize_${T}(${T} * arg, unsigned char * buffer){
            unsigned int size = 0;
            ${joinToNode(type.fields, serializeField, { appendNewLineIfNotEmpty: true })}
            (void)arg; (void)buffer;
            return size;
        }

        static inline unsigned int deserialize_${T}(${T} * arg, unsigned char* buffer){
            unsigned int size = 0;
            ${joinToNode(type.fields, deserializeField, { appendNewLineIfNotEmpty: true })}
            (void)arg; (void)buffer;
            return size;
        }

        static inline void set_${T}(${T} * arg1, ${T} * arg2){
            if (arg1 == arg2) return;
            ${joinToNode(type.fields, setField, { appendNewLineIfNotEmpty: true })}
            ${type.fields.length === 0 ? '*arg1 = *arg2;' : undefined}
        }

        /* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
           characters read, or -1 (then *arg is unchanged) */
        static inline int get_${T}(${T} * arg, char* description){
            int sizeread = 0, res = 0;
            char symbol = '{';
            ${T} tmp;
            if (arg == NULL || description == NULL) return -1;
            set_${T}(&tmp, arg);
            if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
            sizeread += res;
            ${type.fields.length === 0 ? expandToNode`
                symbol = '}';
                if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
                sizeread += res;
            ` : joinToNode(getFields, (n) => n, { appendNewLineIfNotEmpty: true })}
            set_${T}(arg, &tmp);
            return sizeread;
        }

        static inline void print_${T}(${T} * arg){
            printf("(object type %s : ", "${T}");
            ${type.fields.length === 0 ? '(void)arg;' : joinToNode(type.fields, printField, { appendNewLineIfNotEmpty: true })}
            printf(")");
        }

        //functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

        static inline int eq_${T}(${T} * arg1, ${T} * arg2){
            ${blockRegion(`protect_eq_${T}`, comparisonBody(type.fields, '=='))}
        }

        static inline int diff_${T}(${T} * arg1, ${T} * arg2){
            ${blockRegion(`protect_diff_${T}`, `if (eq_${T}(arg1,arg2) == 0) return 1;\nreturn 0;\n`)}
        }

        static inline int inf_${T}(${T} * arg1, ${T} * arg2){
            ${blockRegion(`protect_inf_${T}`, comparisonBody(type.fields, '<'))}
        }

        static inline int sup_${T}(${T} * arg1, ${T} * arg2){
            ${blockRegion(`protect_sup_${T}`, comparisonBody(type.fields, '>'))}
        }

        static inline int infeq_${T}(${T} * arg1, ${T} * arg2){
            ${blockRegion(`protect_infeq_${T}`, `if (inf_${T}(arg1,arg2) == 1 || eq_${T}(arg1,arg2) == 1)\n    return 1;\nreturn 0;\n`)}
        }

        static inline int supeq_${T}(${T} * arg1, ${T} * arg2){
            ${blockRegion(`protect_supeq_${T}`, `if (sup_${T}(arg1,arg2) == 1 || eq_${T}(arg1,arg2) == 1)\n    return 1;\nreturn 0;\n`)}
        }

        //from here you can define new functions for your newly defined type
        ${blockRegion(`protect_additional_impl_${T}`, '//TODO')}

        #endif
    `;
    return toString(node) + '\n';
}
