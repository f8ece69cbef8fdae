// Monarch syntax highlighting for the cactal language.
export default {
    keywords: [
        'ORD','activate','and','asynchronous','bool','communications','compute','configuration','const','critical','data','datatype','duration','elapsed','endof','enum','event','false','float','flows','function','graph','import','in','infinite','int','local','module','modules','notify','or','ord_schema','out','parameterize','parameters','periodic','realtime','resttime','rules','scheduler','scheduling','schema','schemas','started','string','subscribe','supervisor','synchronous','true','void'
    ],
    operators: [
        '!=','&','*',',','->','.',':',';','<','<=','=','=*','==','==*','==>','=>','>','>=','|'
    ],
    symbols: /!=|&|\(|\)|\*|,|->|\.|:|;|<|<=|=|=\*|==|==\*|==>|=>|>|>=|\[|\]|\{|\||\}/,

    tokenizer: {
        initial: [
            { regex: /-?[0-9]+(\.[0-9]+)?(ns|us|ms|s)/, action: {"token":"TIME"} },
            { regex: /-?([0-9]+\.[0-9]*([eE][-+]?[0-9]+)?|\.[0-9]+([eE][-+]?[0-9]+)?|[0-9]+[eE][-+]?[0-9]+)/, action: {"token":"number"} },
            { regex: /-?[0-9]+/, action: {"token":"number"} },
            { regex: /[A-Za-z_][A-Za-z0-9_]*/, action: { cases: { '@keywords': {"token":"keyword"}, '@default': {"token":"ID"} }} },
            { regex: /"(\\.|[^"\\\r\n])*"/, action: {"token":"string"} },
            { include: '@whitespace' },
            { regex: /@symbols/, action: { cases: { '@operators': {"token":"operator"}, '@default': {"token":""} }} },
        ],
        whitespace: [
            { regex: /\s+/, action: {"token":"white"} },
            { regex: /\/\*/, action: {"token":"comment","next":"@comment"} },
            { regex: /\/\/[^\n\r]*/, action: {"token":"comment"} },
        ],
        comment: [
            { regex: /[^/\*]+/, action: {"token":"comment"} },
            { regex: /\*\//, action: {"token":"comment","next":"@pop"} },
            { regex: /[/\*]/, action: {"token":"comment"} },
        ],
    }
};
