// Meld.g4 — grammar of Linear Meld as accepted by meldc (docs/meld-language.md §1–§5).
//
// Differences from cl-meld, all of them a harmless superset (spec §11):
//  * `/* ... */` comments may span lines; `//` comments always run to the end of the line;
//  * a negative literal is a parser construct ('-' NUMBER), so `X-1` and `5-1` are subtractions;
//  * the order of the sections (include, type, directives, extern, const, fun, rules) is checked
//    by the AST builder with a clear diagnostic instead of being a syntax error;
//  * the header words (index, compact, data, priority, allocator) may also be used as names.
// Keywords are case-insensitive but, like every identifier, start with a lower-case letter.
grammar Meld;

// ---------------------------------------------------------------------------------------------
// Parser
// ---------------------------------------------------------------------------------------------

program : topItem* EOF ;

// Entry point for -DNAME=VALUE values on the command line.
standaloneExpr : expr EOF ;

topItem
  : includeDecl
  | definition
  | directive
  | externDecl
  | constDecl
  | funDecl
  | statement
  ;

includeDecl : K_INCLUDE FILE ;

definition
  : K_NODE name DOT                                                              # nodeTypeDef
  | K_TYPE typeExpr name DOT                                                     # typeAliasDef
  | K_TYPE predModifier* name LPAREN fieldDecls? RPAREN DOT                      # predicateDef
  | K_IMPORT predModifier* name LPAREN fieldDecls? RPAREN K_AS name K_FROM name DOT # importDef
  | K_EXPORT name DOT                                                            # exportDef
  ;

predModifier : K_LINEAR | K_ROUTE | K_ACTION ;

fieldDecls : fieldDecl (COMMA fieldDecl)* ;
fieldDecl  : aggMod? typeExpr VARIABLE? ;
aggMod     : K_MIN | IDENT ;

typeExpr
  : K_INT                                          # intType
  | K_FLOAT                                        # floatType
  | K_BOOL                                         # boolType
  | K_STRING                                       # stringType
  | K_NODE                                         # nodeType
  | K_THREAD                                       # threadType
  | name                                           # namedType
  | K_LIST typeExpr                                # listType
  | K_SET typeExpr                                 # setType
  | K_ARRAY typeExpr                               # arrayType
  | STRUCT_OPEN typeExpr (COMMA typeExpr)* RPAREN  # structType
  ;

directive
  : K_INDEX name SLASH INT DOT                            # indexDirective
  | K_COMPACT name DOT                                    # compactDirective
  | K_DATA name STRING (LBRACK STRING* RBRACK)? DOT       # dataDirective
  | K_ALLOCATOR STRING DOT                                # allocatorDirective
  | K_PRIORITY priorityArg DOT                            # priorityDirective
  ;

priorityArg
  : P_STATIC                          # prioStatic
  | P_CLUSTER P_STATIC                # prioClusterStatic
  | P_CLUSTER P_RANDOM                # prioClusterRandom
  | P_NO_INITIAL                      # prioNoInitial
  | P_INITIAL number                  # prioInitial
  | P_DEFAULT number                  # prioDefault
  | P_NO_PRIORITY number              # prioNoPriority
  | P_ORDER P_ASC                     # prioAsc
  | P_ORDER P_DESC                    # prioDesc
  | name op=(LT | GT) name            # prioRelation
  ;

number : MINUS? (INT | FLOAT) ;

externDecl : K_EXTERN typeExpr name LPAREN fieldDecls? RPAREN DOT ;

constDecl : K_CONST name EQ expr DOT ;

funDecl : K_FUN name LPAREN (funParam (COMMA funParam)*)? RPAREN COLON typeExpr EQ expr DOT ;
funParam : typeExpr VARIABLE ;

// Factored so that each decision needs little lookahead: a missing '.' is then reported where it
// belongs instead of as "no viable alternative" at the start of the next statement.
statement
  : selector LOLLI head? DOT                          # selectorRule
  | IMPLIEDBY terms DOT                               # headlessDatalogRule
  | terms ( LOLLI head? | IMPLIEDBY terms )? DOT      # plainStatement   // body -o head | head :- body | fact
  ;

selector : LBRACK COLON kind=(K_MIN | K_RANDOM) VARIABLE BAR terms RBRACK ;

head : INT | terms ;

terms : term (COMMA term)* ;

// An unmarked subgoal `p(X)` is parsed as a call condition (condTerm) and turned into a subgoal by
// the AST builder: the two are the same text, and one path keeps the parser free of ambiguity.
term
  : mark=(BANG | QUESTION | DOLLAR) name LPAREN args RPAREN DELAY?                  # subgoalTerm
  | K_EXISTS varList DOT LPAREN terms RPAREN                                         # existsTerm
  | LBRACE (varList | DOT)? BAR terms BAR head? RBRACE                               # comprehensionTerm
  | LBRACK aggSpec (COMMA aggSpec)* (BAR aggSection)+ RBRACK                         # aggregateTerm
  | LPAREN K_IF cond K_THEN head K_OTHERWISE head K_END RPAREN                        # conditionalTerm
  | cond DELAY?                                                                      # condTerm
  ;

varList : VARIABLE (COMMA VARIABLE)* ;

aggSpec
  : op=(K_MIN | IDENT) FATARROW VARIABLE          # simpleAggSpec
  | K_CUSTOM name expr FATARROW VARIABLE          # customAggSpec
  ;

aggSection
  : varList
  | head
  |
  ;

args : expr (COMMA expr)* ;

cond
  : NOT cond                                       # notCond
  | <assoc=right> cond AND cond                    # andCond
  | <assoc=right> cond OR cond                     # orCond
  | expr op=(EQ | NE | LT | LE | GT | GE) expr     # compareCond
  | expr op=(K_IN | K_INS) expr                    # inCond
  | LPAREN cond RPAREN                             # parenCond
  | name LPAREN args RPAREN                        # callCond
  ;

expr
  : expr op=(STAR | SLASH | PERCENT) expr          # mulExpr
  | expr op=(PLUS | MINUS | PLUSPLUS) expr         # addExpr
  | primary                                        # primaryExpr
  ;

primary
  : VARIABLE                                       # varExpr
  | UNDERSCORE                                     # anonExpr
  | ARG                                            # argExpr
  | K_TRUE                                         # trueExpr
  | K_FALSE                                        # falseExpr
  | STRING                                         # stringExpr
  | MINUS? INT                                     # intExpr
  | MINUS? FLOAT                                   # floatExpr
  | name LPAREN args? RPAREN                       # callExpr
  | name                                           # constExpr
  | AT INT                                         # nodeExpr
  | kind=(S_WORLD | S_CPUS | S_HOST | S_THREAD)    # specialExpr
  | LPAREN expr RPAREN                             # parenExpr
  | STRUCT_OPEN expr (COMMA expr)* RPAREN          # structExpr
  | K_FLOAT LPAREN expr RPAREN                     # convExpr
  | K_IF cond K_THEN expr K_ELSE expr K_END        # ifExpr
  | K_LET VARIABLE EQ expr K_IN expr K_END         # letExpr
  | K_NIL                                          # nilExpr
  | LBRACK (expr (COMMA expr)* (BAR expr)?)? RBRACK # listExpr
  ;

// Predicate, constant, function and extern names. The header-only words are names too.
name : IDENT | QIDENT | K_INDEX | K_COMPACT | K_DATA | K_PRIORITY | K_ALLOCATOR ;

// ---------------------------------------------------------------------------------------------
// Lexer (longest match; on equal length the rule listed first wins)
// ---------------------------------------------------------------------------------------------

LINE_COMMENT  : '//' ~[\r\n]* -> skip ;
BLOCK_COMMENT : '/*' .*? '*/' -> skip ;
// An unterminated block comment runs to the end of the file (it never contains '*/').
UNTERMINATED_COMMENT : '/*' ( ~'*' | '*'+ ~[*/] )* '*'* -> channel(HIDDEN) ;
WS : [ \t\r\n\f]+ -> skip ;

INT    : [0-9]+ ;
FLOAT  : [0-9]+ '.' [0-9]+ ;
STRING : '"' ~["\r\n]* '"' ;
BAD_STRING : '"' ~["\r\n]* -> channel(HIDDEN) ;

DELAY  : '@+' [0-9]+ ( 's' | 'ms' ) ;
ARG    : '@arg' [0-9] ;
S_WORLD  : '@world' ;
S_CPUS   : '@cpus' ;
S_HOST   : '@host' ;
S_THREAD : '@thread' ;
P_INITIAL    : '@initial' ;
P_STATIC     : '@static' ;
P_CLUSTER    : '@cluster' ;
P_RANDOM     : '@random' ;
P_NO_INITIAL : '@no_initial_priorities' ;
P_NO_PRIORITY: '@no_priority' ;
P_DEFAULT    : '@default' ;
P_ASC        : '@asc' ;
P_DESC       : '@desc' ;
P_TYPE       : '@type' ;
P_ORDER      : '@order' ;
AT     : '@' ;

LOLLI       : '-o' ;
IMPLIEDBY   : ':-' ;
STRUCT_OPEN : ':(' ;
FATARROW    : '=>' ;
COLON     : ':' ;
COMMA     : ',' ;
DOT       : '.' ;
LPAREN    : '(' ;
RPAREN    : ')' ;
LBRACK    : '[' ;
RBRACK    : ']' ;
LBRACE    : '{' ;
RBRACE    : '}' ;
NOT       : '~' ;
BANG_EQ   : '!=' ;       // not Meld; lexed only to give a helpful message
EQ_EQ     : '==' ;       // idem
BANG      : '!' ;
QUESTION  : '?' ;
DOLLAR    : '$' ;
OR        : '||' ;
BAR       : '|' ;
AND       : '&&' ;
PLUSPLUS  : '++' ;
PLUS      : '+' ;
MINUS     : '-' ;
STAR      : '*' ;
PERCENT   : '%' ;
SLASH     : '/' ;
LE        : '<=' ;
NE        : '<>' ;
LT        : '<' ;
GE        : '>=' ;
GT        : '>' ;
EQ        : '=' ;
UNDERSCORE: '_' ;

K_TYPE      : 't' Y P E ;
K_EXISTS    : 'e' X I S T S ;
K_EXTERN    : 'e' X T E R N ;
K_CONST     : 'c' O N S T ;
K_BOOL      : 'b' O O L ;
K_INT       : 'i' N T ;
K_FLOAT     : 'f' L O A T ;
K_NODE      : 'n' O D E ;
K_THREAD    : 't' H R E A D ;
K_STRING    : 's' T R I N G ;
K_LIST      : 'l' I S T ;
K_SET       : 's' E T ;
K_ARRAY     : 'a' R R A Y ;
K_INCLUDE   : 'i' N C L U D E ;
K_RANDOM    : 'r' A N D O M ;
K_ROUTE     : 'r' O U T E ;
K_ACTION    : 'a' C T I O N ;
K_LINEAR    : 'l' I N E A R ;
K_EXPORT    : 'e' X P O R T ;
K_IMPORT    : 'i' M P O R T ;
K_CUSTOM    : 'c' U S T O M ;
K_FROM      : 'f' R O M ;
K_AS        : 'a' S ;
K_LET       : 'l' E T ;
K_INS       : 'i' N S ;
K_IN        : 'i' N ;
K_END       : 'e' N D ;
K_IF        : 'i' F ;
K_THEN      : 't' H E N ;
K_FUN       : 'f' U N ;
K_ELSE      : 'e' L S E ;
K_OTHERWISE : 'o' T H E R W I S E ;
K_MIN       : 'm' I N ;
K_TRUE      : 't' R U E ;
K_FALSE     : 'f' A L S E ;
K_NIL       : 'n' I L ;
K_ALLOCATOR : 'a' L L O C A T O R ;
K_PRIORITY  : 'p' R I O R I T Y ;
K_INDEX     : 'i' N D E X ;
K_COMPACT   : 'c' O M P A C T ;
K_DATA      : 'd' A T A ;

IDENT    : [a-z] [a-zA-Z0-9_?-]* ;
QIDENT   : '\'' [A-Za-z0-9_]+ ;
VARIABLE : [A-Z] [a-zA-Z0-9_]* ;
FILE     : '#' ~[\r\n]* ;

// Anything else: cl-meld skips characters no token can start with; we skip them with a warning.
STRAY : . -> channel(HIDDEN) ;

fragment A : [aA] ; fragment B : [bB] ; fragment C : [cC] ; fragment D : [dD] ;
fragment E : [eE] ; fragment F : [fF] ; fragment G : [gG] ; fragment H : [hH] ;
fragment I : [iI] ; fragment J : [jJ] ; fragment K : [kK] ; fragment L : [lL] ;
fragment M : [mM] ; fragment N : [nN] ; fragment O : [oO] ; fragment P : [pP] ;
fragment Q : [qQ] ; fragment R : [rR] ; fragment S : [sS] ; fragment T : [tT] ;
fragment U : [uU] ; fragment V : [vV] ; fragment W : [wW] ; fragment X : [xX] ;
fragment Y : [yY] ; fragment Z : [zZ] ;
