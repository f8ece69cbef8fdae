/**
 * The blocks of a module or schema body come in a fixed order, each at most once (docs/language-reference.md §3, §4).
 * module-checks.ts and schema-checks.ts give the order, the block names and their codes.
 */
import type { AstNode, ValidationAcceptor } from 'langium';
import type { DiagnosticCode } from './codes/code-table.js';
import { report } from './report.js';

export interface BlockOrder<B extends AstNode, N extends string> {
    /** The order the blocks must come in. */
    order: readonly N[];
    nameOf(block: B): N;
    /** The keyword a diagnostic on the block underlines. */
    keywordOf(block: B): string;
    /** Code of a block that repeats an earlier one. */
    duplicate: DiagnosticCode;
    /** Code of a block written after one that must follow it. */
    outOfOrder: DiagnosticCode;
}

/** Reports each block that repeats an earlier one or comes after a block that must follow it; `owner` is e.g. `Module MSA`. */
export function checkBlockOrder<B extends AstNode, N extends string>(
    owner: string, blocks: readonly B[], rules: BlockOrder<B, N>, accept: ValidationAcceptor
): void {
    const seen: N[] = [];
    for (const block of blocks) {
        const name = rules.nameOf(block);
        const at = { node: block, keyword: rules.keywordOf(block) };
        if (seen.includes(name)) {
            report(accept, rules.duplicate, `${owner} already has a '${name}' block: merge them into one.`, at);
            continue;
        }
        const rank = rules.order.indexOf(name);
        const later = seen.find((s) => rules.order.indexOf(s) > rank);
        if (later) report(accept, rules.outOfOrder, `Block '${name}' must come before '${later}': the order is ${rules.order.join(', ')}.`, at);
        seen.push(name);
    }
}
