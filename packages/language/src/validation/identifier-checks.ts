/**
 * Identifiers become C names as they are (report §5.3): no C keyword, no leading `_`.
 */
import type { AstNode, ValidationAcceptor, ValidationChecks } from 'langium';
import type { CactalAstType } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { ModuleCodes } from './codes/modules.js';
import { report } from './report.js';

/** C11 keywords, plus bool/true/false (C23 keywords, stdbool.h macros). */
export const C_KEYWORDS = new Set([
    'auto', 'break', 'case', 'char', 'const', 'continue', 'default', 'do', 'double', 'else', 'enum', 'extern',
    'float', 'for', 'goto', 'if', 'inline', 'int', 'long', 'register', 'restrict', 'return', 'short', 'signed',
    'sizeof', 'static', 'struct', 'switch', 'typedef', 'union', 'unsigned', 'void', 'volatile', 'while',
    '_Alignas', '_Alignof', '_Atomic', '_Bool', '_Complex', '_Generic', '_Imaginary', '_Noreturn', '_Static_assert',
    '_Thread_local', 'bool', 'true', 'false'
]);

const NAMED_TYPES = [
    'DataType', 'Field', 'FunctionPrototype', 'FunctionArgument', 'Module', 'Parameter', 'Port', 'Schema',
    'SchemaParameter', 'Supervisor', 'SupervisionFunction', 'FunctionParameter', 'LocalVariable', 'Rule'
] as const;

function checkIdentifier(node: AstNode & { name?: string }, accept: ValidationAcceptor): void {
    const name = node.name;
    if (!name) return;
    if (C_KEYWORDS.has(name)) {
        report(accept, ModuleCodes['identifier-c-keyword'], `'${name}' is a C keyword and the generated C uses Cactal names as they are: choose another name (e.g. '${name}_').`, { node, property: 'name' as never });
    } else if (name.startsWith('_')) {
        report(accept, ModuleCodes['identifier-reserved-prefix'], `'${name}' starts with '_', which is reserved for generated code: choose a name starting with a letter.`, { node, property: 'name' as never });
    }
}

export function identifierChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    const checks: Record<string, typeof checkIdentifier> = {};
    for (const type of NAMED_TYPES) checks[type] = checkIdentifier;
    return checks as ValidationChecks<CactalAstType>;
}
