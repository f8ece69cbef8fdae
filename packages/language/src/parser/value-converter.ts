/**
 * Reads a string literal with the language's escapes (model/strings.ts), the same as a scenario and
 * the runtime do. Langium's default reader also took `\v` for a vertical tab, which the scenario
 * reader and the runtime read as `v`.
 */
import { DefaultValueConverter, type CstNode, type GrammarAST, type ValueType } from 'langium';
import { unescapeString } from '../model/strings.js';

export class CactalValueConverter extends DefaultValueConverter {
    protected override runConverter(rule: GrammarAST.AbstractRule, input: string, cstNode: CstNode): ValueType {
        if (rule.name === 'STRING') return unescapeString(input.slice(1, -1));
        return super.runConverter(rule, input, cstNode);
    }
}
