/**
 * The protected regions that still mention a renamed entity's old name, as the terminal lists them
 * after a rename (`contract rename`) and after finishing one that was killed half-way (`contract
 * generate`): a use in code (or an `#include` of a renamed header) is a warning, the build fails
 * until it is changed by hand; one in a comment or a literal is a note. docs/codegen.md, "Your code
 * that uses the renamed name".
 */
import type { RegionMention } from '@contract-studio/codegen';
import type { CliIO } from './command.js';
import { safeName } from './terminal-text.js';

/** Kinds whose names the generated C or the user code uses (a schema or a supervision function is in no module's C). */
export const MENTIONED_KINDS: ReadonlySet<string> = new Set(['module', 'supervisor', 'datatype', 'enumeration', 'enumeration member', 'function', 'port', 'parameter']);

/**
 * Prints `mentions` of the old name `oldName` (files relative to the tree, named for the reader by
 * `inTree`); the number of them the build needs changed (in code, or an `#include` of a header
 * named after the entity, which is gone).
 */
export function printRegionMentions(io: CliIO, mentions: readonly RegionMention[], oldName: string, inTree: (file: string) => string): number {
    let inCode = 0;
    for (const m of mentions) {
        const where = `${inTree(m.file)}:${m.line}: protected region ${safeName(m.id)}`;
        // a header named after the entity is gone: an #include of it fails like code does
        if (m.context === 'code' || (m.word !== oldName && m.word.startsWith('Shared'))) {
            inCode++;
            io.err(`warning: ${where} still uses ${safeName(m.word)} (the old name) ${m.context === 'code' ? 'in its code' : 'in an #include'}: change it by hand, the build fails until then\n`);
        } else {
            io.err(`note: ${where} mentions ${safeName(m.word)} (the old name) in a ${m.context === 'comment' ? 'comment' : 'string or character literal'}: not changed\n`);
        }
    }
    return inCode;
}
