import type { ValidationChecks } from 'langium';
import type { CactalAstType } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';

export function importChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    return {};
}
