import { expandToNode, joinToNode, toString } from 'langium/generate';
import type { FunctionPrototype, TypeRef } from '../model/architecture.js';
import { cDeclaration, cType, isCArray } from './c/c-syntax.js';
import { namedTypeOf } from '../model/lookup.js';
import { blockRegion } from './c/regions.js';
import { architecturePath } from '@contract-studio/conventions';

/** `common/SharedFunction<f>.h`: a user test/compute function (report §5.2), arguments by pointer. */
export function sharedFunctionPath(name: string): string {
    return architecturePath(`common/SharedFunction${name}.h`);
}

/** `char *`, `long *`, `double *`, `TypeA *`: every argument by pointer (docs/codegen.md "The tree": so that compute functions can assign the locals). */
export function cPointerType(t: TypeRef): string {
    // an array argument is a pointer to its first element: `double *` for float[6], `double (*)[3]` for float[3][3]
    if ('array' in t && isCArray(t.array)) return cDeclaration(t.array, '(*)');
    if ('array' in t) return `${cType(t.array)} *`;
    return `${cType(t)} *`;
}

/** The declaration of an argument `name` by pointer. */
export function cPointerDeclaration(t: TypeRef, name: string): string {
    if ('array' in t && isCArray(t.array)) return cDeclaration(t.array, `(* ${name})`);
    return `${cPointerType(t)} ${name}`;
}

/** The C prototype text of a user function: `int testit(char * arg1, TypeA * arg2)`. */
export function cFunctionSignature(f: FunctionPrototype): string {
    const ret = f.returns === 'bool' ? 'int' : 'void';
    const args = f.args.length ? f.args.map((a) => cPointerDeclaration(a.type, a.name)).join(', ') : 'void';
    return `${ret} ${f.name}(${args})`;
}

export function generateSharedFunctionHeader(f: FunctionPrototype): string {
    const guard = `SHARED_FUNCTION_${f.name.toUpperCase()}_H`;
    const deps = [...new Set(f.args.flatMap((a) => namedTypeOf(a.type) ?? []))];
    const usesBool = f.args.some((a) => cType(a.type) === 'bool');
    const unused = f.args.map((a) => `(void)${a.name};`).join(' ');
    const body = (unused ? `${unused} //remove once the arguments are used\n` : '') + '//TODO\n' +
        (f.returns === 'bool' ? 'return 0;//return 0 when result is false otherwise must return 1\n' : '');
    const node = expandToNode`
        #ifndef ${guard}
        #define ${guard}
        #include <stdio.h>
        #include <string.h>
        ${usesBool ? '#include <stdbool.h>' : undefined}
        #include "tools.h"
        ${joinToNode(deps, (d) => `#include "Shared${d}.h"`, { appendNewLineIfNotEmpty: true })}

        //from here you can make inclusions and definitions
        ${blockRegion(`protect_additional_import_function_${f.name}`, '//TODO')}

        static inline ${cFunctionSignature(f)};

        static inline ${cFunctionSignature(f)}{
            ${blockRegion(`protect_function_impl_${f.name}`, body)}
        }

        #endif
    `;
    return toString(node) + '\n';
}
