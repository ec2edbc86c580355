// SMQL, the smql query language. docs/language.md is the user reference.
//
// The parser (engine/parser/parser.cpp) splits a script into statements at
// `;` and parses each one with the `statement` rule, so the grammar never sees
// the separators. Checks that need words rather than token types (clause
// order, sides, units, LIMIT values) live in the tree walker, where they can
// say what is wrong in plain words.
grammar Smql;

// ---------------------------------------------------------------- statements

statement    : EXPLAIN? command EOF ;

command      : findStmt | countStmt | relateStmt | describeStmt | showStmt | useStmt | setStmt
             | askStmt | checkStmt | dropStmt | renameStmt | guideStmt
             ;

// Clauses are a loop rather than a fixed sequence: the walker checks their
// order and reports "WHERE must come before LIMIT" instead of a bare
// "unexpected WHERE", and lets PATH stand anywhere after the target.
findStmt     : FIND ref findClause* ;
findClause   : viewClause | whereClause | nearestClause | orderClause | limitClause | PATH | asOfClause
             | returnClause | similarClause ;

countStmt    : COUNT ref countClause* ;
countClause  : viewClause | whereClause | asOfClause ;

relateStmt   : RELATE ref TO ref viewClause? ;
describeStmt : DESCRIBE ref ;
// `CHECK lamp left_of window`, `CHECK mug near window 1 m`, `CHECK lamp between sofa AND desk`:
// yes or no for one predicate over single nodes.
checkStmt    : CHECK ref name ref ( AND ref )? distance? viewClause? ;
showStmt     : SHOW ( SCENES | TREE ref? | SETTINGS | CHANGES ( SINCE STRING )? | GRAPH | CATEGORIES | ATTRIBUTES ) ;
// `USE SCENE *` (or `all`): every scene at once.
useStmt      : USE SCENE ( name | STRING | STAR ) ;
setStmt      : SET settingName EQ setValue ;
settingName  : name ( DOT name )* ;
setValue     : quantity | STRING | name ;
// `ASK 'where is the mug?'`: a question in English, translated to SMQL by engine/ask.
askStmt      : ASK STRING ;
// Scenes by name, in one write transaction each (docs/history.md).
dropStmt     : DROP SCENE sceneName ;
renameStmt   : RENAME SCENE sceneName TO sceneName ;
sceneName    : name | STRING ;
// `GUIDE FROM door TO (FIND mug LIMIT 1)`: a route in steps (docs/guidance.md). HERE is the
// scene's viewpoint; a point is (x, y) in metres in the scene's frame.
guideStmt    : GUIDE FROM guideOrigin TO ref ;
guideOrigin  : HERE | floorPoint | ref ;
floorPoint   : LPAREN MINUS? NUMBER COMMA MINUS? NUMBER RPAREN ;

viewClause    : VIEW FROM ref ( FACING ref )? ;
whereClause   : WHERE orExpr ;
nearestClause : NEAREST TO placeRef ;
// `SIMILAR TO 'soft thing to sit on'`: rows ranked by the similarity of their text (docs/similarity.md).
similarClause : SIMILAR TO ( STRING | PARAM ) ;
orderClause   : ORDER BY measure ( ASC | DESC )? ;
// `RETURN id, color, center`: the columns FIND answers with, in that order.
returnClause  : RETURN name ( COMMA name )* ;
// What ORDER BY and comparisons measure: the distance to a reference, or an attribute (`height`).
measure       : DISTANCE LPAREN placeRef RPAREN | name ;
// What a distance is measured to and a predicate relates to: nodes, or HERE, where the viewer stands
// (the statement's viewpoint).
placeRef      : HERE | ref ;
limitClause   : LIMIT ( MINUS? NUMBER | PARAM ) ;
// `AS OF '2026-11-20'`: the scene as the memory held it then (docs/history.md).
asOfClause    : AS OF STRING ;

// ---------------------------------------------------------------- references

ref          : namedRef | NODE_ID | SOURCE_ID | LABELLED_ID | subQuery ;
// A placeholder (`?`, `$1`) stands for a name bound when a prepared statement runs
// (docs/language.md, "Parameters"); in a predicate's last argument it may stand for the distance.
namedRef     : ( name | STRING | PARAM ) ( DOT side=name )? ;
subQuery     : LPAREN FIND ref findClause* RPAREN ;

// ---------------------------------------------------------------- conditions
// NOT binds tighter than AND, AND tighter than OR.

orExpr       : andExpr ( OR andExpr )* ;
andExpr      : notExpr ( AND notExpr )* ;
notExpr      : NOT notExpr | atom ;
atom         : LPAREN orExpr RPAREN | predicate | comparison | changedSince ;
predicate    : name LPAREN placeRef ( COMMA placeRef )* ( COMMA distance )? RPAREN ;
// `detected_as IS NOT NULL`: whether the node has the attribute at all.
comparison   : measure ( compareOp quantityOrString | BETWEEN quantity AND quantity | IS NOT? NULL_ ) ;
// `moved SINCE '2026-11-20'`, `added SINCE ...`, `seen SINCE ...`: the walker checks the word.
changedSince : name SINCE STRING ;
compareOp    : EQ | NE | LT | LE | GT | GE | LIKE ;
quantityOrString : quantity | STRING | PARAM ;

// A unit is any identifier here; the walker accepts m, cm and mm and names
// anything else, which reads better than a token-level error.
quantity     : MINUS? NUMBER unit=IDENT? ;
distance     : NUMBER unit=IDENT? ;

// Every keyword except the logical ones can also be a name, so a category
// called `scene`, `tree` or `path`, or a setting called `limit`, still works.
name         : IDENT
             | FIND | COUNT | RELATE | DESCRIBE | SHOW | USE | SET | EXPLAIN
             | VIEW | FROM | FACING | WHERE | NEAREST | TO | ORDER | BY | DISTANCE | ASC | DESC
             | LIMIT | PATH | SCENES | SCENE | TREE | SETTINGS
             | ASK | CHECK | DROP | RENAME | CATEGORIES | ATTRIBUTES | BETWEEN | RETURN | CHANGES | SINCE | AS | OF
             | GUIDE | HERE | GRAPH | SIMILAR
             ;

// ---------------------------------------------------------------- tokens
// Keywords are case-insensitive. Their order here is the order hints list
// them in ("expected VIEW FROM, WHERE, NEAREST TO, ...").

FIND     : F I N D ;
COUNT    : C O U N T ;
RELATE   : R E L A T E ;
DESCRIBE : D E S C R I B E ;
SHOW     : S H O W ;
USE      : U S E ;
SET      : S E T ;
ASK      : A S K ;
CHECK    : C H E C K ;
DROP     : D R O P ;
RENAME   : R E N A M E ;
GUIDE    : G U I D E ;
EXPLAIN  : E X P L A I N ;
VIEW     : V I E W ;
FROM     : F R O M ;
FACING   : F A C I N G ;
WHERE    : W H E R E ;
NEAREST  : N E A R E S T ;
SIMILAR  : S I M I L A R ;
TO       : T O ;
ORDER    : O R D E R ;
BY       : B Y ;
DISTANCE : D I S T A N C E ;
ASC      : A S C ;
DESC     : D E S C ;
LIMIT    : L I M I T ;
PATH     : P A T H ;
SCENES   : S C E N E S ;
SCENE    : S C E N E ;
TREE     : T R E E ;
SETTINGS : S E T T I N G S ;
CATEGORIES : C A T E G O R I E S ;
ATTRIBUTES : A T T R I B U T E S ;
BETWEEN  : B E T W E E N ;
RETURN   : R E T U R N ;
CHANGES  : C H A N G E S ;
SINCE    : S I N C E ;
AS       : A S ;
OF       : O F ;
HERE     : H E R E ;
GRAPH    : G R A P H ;
IS       : I S ;
NULL_    : N U L L ;
AND      : A N D ;
OR       : O R ;
NOT      : N O T ;
LIKE     : L I K E ;

SOURCE_ID : S R C '#' [0-9]+ ;
NODE_ID   : '#' [0-9]+ ;
// `sofa#50`, as results print a node: its category and id (the binder checks they agree).
LABELLED_ID : [a-zA-Z_] [a-zA-Z0-9_]* ( '-' [a-zA-Z0-9_]+ )* '#' [0-9]+ ;

// Letters, digits and `_`, with single hyphens inside (`plant-stand`); a
// hyphen must be followed by a letter or digit, so `a--note` is `a` plus a
// comment.
IDENT    : [a-zA-Z_] [a-zA-Z0-9_]* ( '-' [a-zA-Z0-9_]+ )* ;
NUMBER   : [0-9]+ ( '.' [0-9]* )? | '.' [0-9]+ ;
// A placeholder: `?` (numbered in order) or `$1`, `$2`, ... (docs/language.md, "Parameters").
PARAM    : '?' | '$' [0-9]+ ;

// A quote inside a string is written twice: 'it''s'. Strings may span lines.
STRING   : '\'' ( ~'\'' | '\'\'' )* '\''
         | '"' ( ~'"' | '""' )* '"'
         ;
// Without its closing quote a string runs to the end of the text; this
// token exists so the walker can say "unterminated string" at the opening
// quote.
UNTERMINATED_STRING : '\'' ( ~'\'' | '\'\'' )* | '"' ( ~'"' | '""' )* ;

EQ     : '=' ;
NE     : '!=' | '<>' ;
LE     : '<=' ;
GE     : '>=' ;
LT     : '<' ;
GT     : '>' ;
LPAREN : '(' ;
RPAREN : ')' ;
COMMA  : ',' ;
DOT    : '.' ;
SEMI   : ';' ;
MINUS  : '-' ;
STAR   : '*' ;

COMMENT : '--' ~[\r\n]* -> skip ;
WS      : [ \t\r\n\f]+ -> skip ;

// Anything else becomes a token the parser rejects with a located message,
// so the lexer itself never fails.
UNKNOWN_CHAR : . ;

fragment A : [aA] ; fragment B : [bB] ; fragment C : [cC] ; fragment D : [dD] ;
fragment E : [eE] ; fragment F : [fF] ; fragment G : [gG] ; fragment H : [hH] ;
fragment I : [iI] ; fragment K : [kK] ; fragment L : [lL] ; fragment M : [mM] ;
fragment N : [nN] ; fragment O : [oO] ; fragment P : [pP] ; fragment R : [rR] ;
fragment S : [sS] ; fragment T : [tT] ; fragment U : [uU] ; fragment V : [vV] ;
fragment W : [wW] ; fragment X : [xX] ; fragment Y : [yY] ;
