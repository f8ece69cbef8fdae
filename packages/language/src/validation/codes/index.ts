/**
 * All diagnostic code tables. Add a new area by creating `codes/<area>.ts` with `defineCodes`
 * and listing it here; docs/diagnostics.md is regenerated from this list.
 */
import type { CodeArea, DiagnosticCode } from './code-table.js';
import { syntaxArea } from './syntax.js';
import { importsArea } from './imports.js';
import { typesArea } from './types.js';
import { modulesArea } from './modules.js';
import { schemasArea } from './schemas.js';
import { schedulerArea } from './scheduler.js';
import { supervisorsArea } from './supervisors.js';
import { architectureArea } from './architecture.js';

export * from './code-table.js';
export { SyntaxCodes } from './syntax.js';
export { ImportCodes } from './imports.js';
export { TypeCodes } from './types.js';
export { ModuleCodes } from './modules.js';
export { SchemaCodes } from './schemas.js';
export { SchedulerCodes } from './scheduler.js';
export { SupervisorCodes } from './supervisors.js';
export { ArchitectureCodes } from './architecture.js';

export const CODE_AREAS: CodeArea[] = [syntaxArea, importsArea, typesArea, modulesArea, schemasArea, schedulerArea, supervisorsArea, architectureArea];

export function allCodes(): DiagnosticCode[] {
    return CODE_AREAS.flatMap((a) => a.codes);
}

export function findCode(code: string): DiagnosticCode | undefined {
    return allCodes().find((c) => c.code === code);
}
export { renderDiagnosticsDoc } from './render-doc.js';
