/**
 * Exports the top-level named elements of a file (datatypes, functions, modules, schemas,
 * supervisors). Local symbols are not precomputed: CactalScopeProvider computes every local
 * scope (ports by index, fields, locals, rule labels) from the AST on demand.
 */
import { DefaultScopeComputation, MultiMap, type AstNode, type AstNodeDescription, type LangiumDocument, type LocalSymbols } from 'langium';

export class CactalScopeComputation extends DefaultScopeComputation {
    override async collectLocalSymbols(_document: LangiumDocument): Promise<LocalSymbols> {
        return new MultiMap<AstNode, AstNodeDescription>();
    }
}
