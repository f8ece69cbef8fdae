import type { ConstantDecl, TypeRef } from '../model/architecture.js';
import { namedTypeOf, type ArchitectureIndex } from '../model/lookup.js';
import { architecturePath } from '@contract-studio/conventions';
import { cDouble, cInitializer, cLongOf, cString, cTypeName } from './c/c-syntax.js';

/**
 * `common/constants.h` (an extension): the named constants (`const int NJOINTS = 6;`) under their
 * Cactal names, so that the code in a module's protected regions writes `NJOINTS` instead of
 * repeating the value. Emitted only when the architecture has constants; every module.c then
 * includes it. Every constant is a macro (docs/codegen.md "Named constants in C"):
 * - int -> `#define NJOINTS (6)`, bool -> `(true)`/`(false)`: integer constant expressions, usable
 *   as array sizes, in `case` labels and in `#if`;
 * - float -> the shortest double literal that reads back as the same double (`(0.3)`);
 * - string -> the escaped string literal (`"base_link"`, no parentheses: it still concatenates);
 * - enumeration -> its C member (`(Mode_AUTO)`);
 * - array or datatype -> a compound literal of the generated C type (`((double[3]){ 1.0, 2.0, 3.0 })`,
 *   `((Pose){ 1.0, 2.0, 0.0 })`), so `HOME.x`, `GAINS[1]` and `Pose p = HOME;` work (not usable in `#if`
 *   or as a static initialiser).
 * The file name is not of the `Shared<T>.h` form, so no datatype can share it.
 */
export const CONSTANTS_HEADER = 'constants.h';

export function constantsHeaderPath(): string {
    return architecturePath(`common/${CONSTANTS_HEADER}`);
}

/** Include guard: `CONTRACT_` names are refused to Cactal elements, so no datatype or constant takes it. */
const GUARD = 'CONTRACT_GENERATED_CONSTANTS_H';

/** The replacement text of the macro of constant `c`. */
function macroBody(c: ConstantDecl, index: ArchitectureIndex): string {
    const t: TypeRef = c.type;
    const v = c.value;
    if ('primitive' in t) {
        switch (t.primitive) {
            case 'int': return `(${v.kind === 'int' || v.kind === 'real' ? cLongOf(v) : '0'})`;
            case 'float': return `(${v.kind === 'int' || v.kind === 'real' ? cDouble(v.value) : '0.0'})`;
            case 'bool': return v.kind === 'bool' && v.value ? '(true)' : '(false)';
            case 'string': return cString(v.kind === 'string' ? v.value : '');
        }
    }
    if ('enum' in t) return `(${cInitializer(index, t, v)})`;
    return `((${cTypeName(t)})${cInitializer(index, t, v)})`;
}

export function generateConstantsHeader(constants: readonly ConstantDecl[], index: ArchitectureIndex): string {
    const types = [...new Set(constants.flatMap((c) => namedTypeOf(c.type) ?? []))];
    const needsBool = constants.some((c) => 'primitive' in c.type && c.type.primitive === 'bool');
    const lines = [
        '//          named constants of the architecture (generated; do not edit)',
        `#ifndef ${GUARD}`,
        `#define ${GUARD}`,
        ...(needsBool ? ['#include <stdbool.h>'] : []),
        ...types.map((t) => `#include "Shared${t}.h"`),
        '',
        ...constants.map((c) => `#define ${c.name} ${macroBody(c, index)}`),
        '',
        '#endif'
    ];
    return lines.join('\n') + '\n';
}
