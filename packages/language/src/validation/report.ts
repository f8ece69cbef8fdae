/** Reporting with a declared code: severity comes from the code table, code goes to `code` and `data.code`. */
import type { AstNode, DiagnosticInfo, ValidationAcceptor } from 'langium';
import type { DiagnosticCode } from './codes/code-table.js';

export type ReportInfo<N extends AstNode> = Omit<DiagnosticInfo<N>, 'code' | 'data'> & { data?: Record<string, unknown> };

export function report<N extends AstNode>(accept: ValidationAcceptor, code: DiagnosticCode, message: string, info: ReportInfo<N>): void {
    accept(code.severity, message, { ...info, code: code.code, data: { ...(info.data ?? {}), code: code.code } } as DiagnosticInfo<N>);
}
