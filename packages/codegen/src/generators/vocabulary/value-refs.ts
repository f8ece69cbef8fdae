import type { PathSegment, TypeRef, Value } from '../../model/architecture.js';
import { cTypeName } from '../c/c-syntax.js';
import type { TableBuilder } from './table-builder.js';

/** What a variable name designates in the context of a table (vocabulary.h ContractRefKind). */
export interface VariableBinding {
    kind: 'CONTRACT_REF_LOCAL' | 'CONTRACT_REF_PARAM' | 'CONTRACT_REF_IN_PORT' | 'CONTRACT_REF_ORD_SCHEMA';
    /** table index, or Cactal port number for IN_PORT */
    index: number;
    type: TypeRef;
}

export type Resolver = (name: string) => VariableBinding | undefined;

/**
 * A path of fields and constant indexes inside a variable of type `root`: the C byte-offset
 * expression and the type at the end. `temp.value` -> `offsetof(TypeC, value)`,
 * `scan.ranges[90]` -> `offsetof(Scan, ranges[90])`, local `q[2]` -> `2 * sizeof(double)`.
 */
export function fieldPath(b: TableBuilder, root: TypeRef, path: PathSegment[]): { offset: string; type: TypeRef } {
    let type = root;
    const terms: string[] = [];
    let struct: string | undefined;
    let designator = '';
    for (const segment of path) {
        if (typeof segment === 'number') {
            if (!('array' in type)) throw new Error(`index [${segment}] of a value that is not an array`);
            if (segment < 0 || segment >= type.size) throw new Error(`index [${segment}] out of range (size ${type.size})`);
            if (struct) designator += `[${segment}]`;
            else terms.push(`${segment} * sizeof(${cTypeName(type.array)})`);
            type = type.array;
            continue;
        }
        if (!('datatype' in type)) throw new Error(`field '${segment}' of a value that is not a datatype`);
        const field = b.index.datatype(type.datatype).fields.find((f) => f.name === segment);
        if (!field) throw new Error(`unknown field '${segment}' of ${type.datatype}`);
        if (struct) designator += `.${segment}`;
        else {
            struct = type.datatype;
            designator = segment;
        }
        type = field.type;
    }
    if (struct) terms.push(`offsetof(${struct}, ${designator})`);
    return { offset: terms.length ? terms.join(' + ') : '0', type };
}

/** Type of a value as written (constants: their literal type; variables: resolved), used for tests. */
export function valueType(b: TableBuilder, v: Value, resolve: Resolver, hint?: TypeRef): TypeRef | undefined {
    switch (v.kind) {
        case 'int':
            return hint && 'primitive' in hint && hint.primitive === 'float' ? hint : { primitive: 'int' };
        case 'real':
            return { primitive: 'float' };
        case 'string':
            return { primitive: 'string' };
        case 'bool':
            return { primitive: 'bool' };
        case 'enum':
            return { enum: v.enum };
        case 'struct':
            return hint;
        case 'var': {
            const binding = resolveVar(resolve, v.name);
            return binding ? fieldPath(b, binding.type, v.path).type : undefined;
        }
    }
}

function resolveVar(resolve: Resolver, name: string): VariableBinding | undefined {
    return name === 'ord_schema' ? { kind: 'CONTRACT_REF_ORD_SCHEMA', index: 0, type: { primitive: 'string' } } : resolve(name);
}

/** A ContractRef initialiser for a value of (target) type `t`: a constant, or a variable with field path. */
export function valueRef(b: TableBuilder, v: Value, t: TypeRef, resolve: Resolver): string {
    if (v.kind === 'var') {
        const binding = resolveVar(resolve, v.name);
        if (!binding) throw new Error(`unknown variable '${v.name}'`);
        const f = fieldPath(b, binding.type, v.path);
        return `{${binding.kind}, ${binding.index}, ${f.offset}, ${b.typeRef(f.type)}, NULL}`;
    }
    return `{CONTRACT_REF_CONST, 0, 0, ${b.typeRef(t)}, ${b.constant(t, v)}}`;
}

function hasVariable(v: Value): boolean {
    return v.kind === 'var' || (v.kind === 'struct' && v.elements.some(hasVariable));
}

/**
 * ContractAssign initialisers giving `value` to variable `target` (+ field path `path`) of type
 * `rootType`: one whole assignment for a constant or a variable, one per field for a structured
 * value that mixes variables.
 */
export function assignments(b: TableBuilder, target: number, rootType: TypeRef, path: PathSegment[], value: Value, resolve: Resolver): string[] {
    const here = fieldPath(b, rootType, path);
    if (value.kind === 'struct' && hasVariable(value) && 'array' in here.type) {
        return value.elements.flatMap((element, i) => assignments(b, target, rootType, [...path, i], element, resolve));
    }
    if (value.kind === 'struct' && hasVariable(value) && 'datatype' in here.type) {
        const fields = b.index.datatype(here.type.datatype).fields;
        return fields.flatMap((f, i) => {
            const element = value.elements[i];
            return element ? assignments(b, target, rootType, [...path, f.name], element, resolve) : [];
        });
    }
    return [`{${target}, ${here.offset}, ${b.typeRef(here.type)}, ${valueRef(b, value, here.type, resolve)}}`];
}

