import type { ValidationChecks } from 'langium';
import type { CactalAstType } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';

export function typeChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    return {};
}
