import type { NamedValue, Value } from '../../model/architecture.js';
import { cDeclaration } from '../c/c-syntax.js';
import type { TableBuilder } from './table-builder.js';

export function isConstant(v: Value | undefined): boolean {
    return v === undefined || (v.kind !== 'var' && (v.kind !== 'struct' || v.elements.every(isConstant)));
}

/**
 * A block of named variables (schema parameters, function parameters, locals): a C struct gives
 * the layout (offsets, size); ContractVar entries carry constant defaults. Returns the C
 * expressions for the ContractVar array, its count and the block size.
 */
export function variableBlock(b: TableBuilder, base: string, vars: NamedValue[]): { array: string; count: number; size: string; structName?: string } {
    if (vars.length === 0) return { array: 'NULL', count: 0, size: '0' };
    const structName = b.unique(`${base}_t`);
    b.define(`typedef struct ${structName} {\n${vars.map((v) => `    ${cDeclaration(v.type, v.name)};`).join('\n')}\n} ${structName};`);
    const items = vars.map((v) => {
        const def = v.default !== undefined && isConstant(v.default) ? b.constant(v.type, v.default) : 'NULL';
        return `{"${v.name}", ${b.typeRef(v.type)}, offsetof(${structName}, ${v.name}), ${def}}`;
    });
    return { array: b.array(base, 'ContractVar', items), count: vars.length, size: `sizeof(${structName})`, structName };
}


