import { expandToNode, joinToNode, toString } from 'langium/generate';
import type { Datatype, Field, TypeRef } from '../model/architecture.js';
import { namedTypeOf } from '../model/lookup.js';
import { cDeclaration, cType } from './c/c-syntax.js';
import { blockRegion, lines } from './c/regions.js';
import { architecturePath } from '@contract-studio/conventions';

/** `common/Shared<Type>.h`: the struct and its functions (report §5.1, §8.2), all `static inline`. */
export function sharedTypePath(name: string): string {
    return architecturePath(`common/Shared${name}.h`);
}

type Kind = 'long' | 'double' | 'string' | 'bool' | 'struct' | 'array';

function kindOf(t: TypeRef): Kind {
    if ('array' in t) return 'array';
    if ('datatype' in t || 'enum' in t) return 'struct'; // enumerations have the same functions (shared-enum-header.ts)
    return t.primitive === 'int' ? 'long' : t.primitive === 'float' ? 'double' : t.primitive;
}
const prim = { long: 'int', double: 'float', string: 'string', bool: 'bool' } as const;

/** Name of a datatype or enumeration (kind 'struct'). */
function named(t: TypeRef): string {
    return 'datatype' in t ? t.datatype : (t as { enum: string }).enum;
}

/** `for (...) {` over the elements of an array lvalue, and the element lvalue. */
function loop(lv: string, t: { array: TypeRef; size: number }, depth: number): { open: string; element: string } {
    const i = `i${depth}`;
    return { open: `for (unsigned int ${i} = 0; ${i} < ${t.size}; ${i}++)`, element: `${lv}[${i}]` };
}

function serializeValue(lv: string, t: TypeRef, depth = 0): string {
    const k = kindOf(t);
    if (k === 'array') {
        const l = loop(lv, t as { array: TypeRef; size: number }, depth);
        return `${l.open} { ${serializeValue(l.element, (t as { array: TypeRef }).array, depth + 1)} }`;
    }
    if (k === 'struct') return `size += serialize_${named(t)}(&${lv}, &buffer[size]);`;
    return `size += extract_${prim[k]}(buffer, size, ${lv});`;
}

function deserializeValue(lv: string, t: TypeRef, depth = 0): string {
    const k = kindOf(t);
    if (k === 'array') {
        const l = loop(lv, t as { array: TypeRef; size: number }, depth);
        return `${l.open} { ${deserializeValue(l.element, (t as { array: TypeRef }).array, depth + 1)} }`;
    }
    if (k === 'struct') return `size += deserialize_${named(t)}(&${lv}, &buffer[size]);`;
    if (k === 'string') return `size += fill_string(${lv}, size, buffer);`;
    return `size += fill_${prim[k]}(&${lv}, size, buffer);`;
}

function serializeField(f: Field): string {
    return serializeValue(`arg->${f.name}`, f.type);
}

function deserializeField(f: Field): string {
    return deserializeValue(`arg->${f.name}`, f.type);
}

function setField(f: Field): string {
    const k = kindOf(f.type);
    if (k === 'struct') return `set_${named(f.type)}(&arg1->${f.name}, &arg2->${f.name});`;
    if (k === 'string' || k === 'array') return `memmove(arg1->${f.name}, arg2->${f.name}, sizeof(arg1->${f.name}));`;
    return `arg1->${f.name}=arg2->${f.name};`;
}

/** The call parsing one value into lvalue `lv` at `&description[sizeread]` (not for arrays). */
function getCall(lv: string, t: TypeRef): string {
    const k = kindOf(t);
    if (k === 'struct') return `get_${named(t)}(&${lv}, &description[sizeread])`;
    if (k === 'string') return `get_string(${lv}, &description[sizeread])`;
    return `get_${prim[k as 'long' | 'double' | 'bool']}(&${lv}, &description[sizeread])`;
}

/** Statements parsing a value of type `t` into `lv` and advancing `sizeread`; arrays are written `{v1, v2, ...}`. */
export function getValue(lv: string, t: TypeRef, depth = 0): string {
    if (!('array' in t)) return `if ((res = ${getCall(lv, t)}) == -1) return -1;\nsizeread += res;`;
    const l = loop(lv, t, depth);
    const marker = (c: string) => `symbol = ${c};\nif ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;\nsizeread += res;`;
    const inner = `${getValue(l.element, t.array, depth + 1)}\n${marker(`i${depth} + 1 < ${t.size} ? ',' : '}'`)}`;
    return `${marker("'{'")}\n${l.open} {\n${indent(inner)}\n}`;
}

function indent(text: string): string {
    return text.split('\n').map((line) => `    ${line}`).join('\n');
}

function printValue(lv: string, t: TypeRef, depth = 0): string {
    switch (kindOf(t)) {
        case 'array': {
            const l = loop(lv, t as { array: TypeRef; size: number }, depth);
            return `printf("["); ${l.open} { if (i${depth} > 0) printf(","); ${printValue(l.element, (t as { array: TypeRef }).array, depth + 1)} } printf("]");`;
        }
        case 'struct': return `print_${named(t)}(&${lv});`;
        case 'string': return `printf("\\"%s\\"", ${lv});`;
        case 'long': return `printf("%ld", ${lv});`;
        case 'double': return `printf("%lf", ${lv});`;
        case 'bool': return `printf("%s", ${lv} ? "true" : "false");`;
    }
}

function printField(f: Field): string {
    switch (kindOf(f.type)) {
        case 'struct':
            return `printf("%s : ", "${f.name}"); print_${named(f.type)}(&arg->${f.name}); printf(" ; ");`;
        case 'array':
            return `printf("%s : ", "${f.name}"); ${printValue(`arg->${f.name}`, f.type)} printf(" ; ");`;
        case 'string':
            return `printf("%s : %s ; ", "${f.name}", arg->${f.name});`;
        case 'long':
            return `printf("%s : %ld ; ", "${f.name}", arg->${f.name});`;
        case 'double':
            return `printf("%s : %lf ; ", "${f.name}", arg->${f.name});`;
        case 'bool':
            return `printf("%s : %s ; ", "${f.name}", arg->${f.name} ? "true" : "false");`;
    }
}

/** The C truth value of `a OP b` for values of type `t` (not arrays); OP one of == < >. */
function compareValues(a: string, b: string, t: TypeRef, op: '==' | '<' | '>'): string {
    const fn = { '==': 'eq', '<': 'inf', '>': 'sup' }[op];
    switch (kindOf(t)) {
        case 'struct':
            return `${fn}_${named(t)}(&${a}, &${b})`;
        case 'string':
            return `strcmp(${a}, ${b}) ${op} 0`;
        default:
            return `${a} ${op} ${b}`;
    }
}

/** `if (!(a.x OP b.x)) return 0;` for a field; arrays: for every element (as the runtime compares arrays). */
function compareField(f: Field, op: '==' | '<' | '>'): string {
    let a = `arg1->${f.name}`;
    let b = `arg2->${f.name}`;
    let t = f.type;
    const loops: string[] = [];
    while ('array' in t) {
        const i = `i${loops.length}`;
        loops.push(`for (unsigned int ${i} = 0; ${i} < ${t.size}; ${i}++) `);
        a += `[${i}]`;
        b += `[${i}]`;
        t = t.array;
    }
    return `${loops.join('')}if (!(${compareValues(a, b, t, op)})) return 0;\n`;
}

/** Default comparison: true when the relation holds for every field (report §8.2). */
function comparisonBody(fields: Field[], op: '==' | '<' | '>'): string {
    if (fields.length === 0) return `(void)arg1; (void)arg2;\nreturn ${op === '==' ? 1 : 0};\n`;
    return fields.map((f) => compareField(f, op)).join('') + 'return 1;\n';
}

export function generateSharedTypeHeader(type: Datatype): string {
    const T = type.name;
    const guard = `SHARED_${T.toUpperCase()}_H`;
    const deps = [...new Set(type.fields.flatMap((f) => namedTypeOf(f.type) ?? []))];
    const usesBool = type.fields.some((f) => cType(f.type) === 'bool');
    const members = type.fields.length > 0 ? type.fields.map((f) => `${cDeclaration(f.type, f.name)};`) : ['char _empty; /* a C struct needs one member */'];
    const getFields = type.fields.map((f, i) => expandToNode`
        ${lines(getValue(`tmp.${f.name}`, f.type))}
        symbol = '${i === type.fields.length - 1 ? '}' : ','}';
        if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
        sizeread += res;
    `);
    const node = expandToNode`
        #ifndef ${guard}
        #define ${guard}
        #include <stdio.h>
        #include <string.h>
        ${usesBool ? '#include <stdbool.h>' : undefined}
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
