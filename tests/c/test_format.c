/*
 * test_format.c - R-style text against R's own output (ref_rformat.h, made by
 * tools/refgen/make_rformat.R): number formatting on ~1600 values, common
 * formatting of pairs, format.pval, and whole print.htest blocks.
 */
#include "harness.h"
#include "mcstat.h"
#include "ref_rformat.h"
#include "rformat.h"

#include <stdlib.h>
#include <string.h>

static void test_numbers(void)
{
    char buf[128];
    for (size_t i = 0; i < REF_NRFMT1; i++) {
        mcstat__rformat1(REF_RFMT1[i].x, REF_RFMT1[i].digits, buf, sizeof buf);
        CHECK_MSG(!strcmp(buf, REF_RFMT1[i].text), "format(%a, digits=%d): got \"%s\", R \"%s\"", REF_RFMT1[i].x,
                  REF_RFMT1[i].digits, buf, REF_RFMT1[i].text);
    }
    for (size_t i = 0; i < REF_NRFMT2; i++) {
        mcstat_rlayout lay;
        mcstat__rformat_layout(REF_RFMT2[i].x, 2, 7, &lay);
        for (int k = 0; k < 2; k++) {
            mcstat__rformat_encode(REF_RFMT2[i].x[k], &lay, 0, buf, sizeof buf);
            CHECK_MSG(!strcmp(buf, REF_RFMT2[i].text[k]), "pair %zu[%d]: got \"%s\", R \"%s\"", i, k, buf,
                      REF_RFMT2[i].text[k]);
        }
    }
    for (size_t i = 0; i < REF_NRPVAL; i++) {
        mcstat__rformat_pval(REF_RPVAL[i].p, 4, buf, sizeof buf);
        CHECK_MSG(!strcmp(buf, REF_RPVAL[i].text), "format.pval(%a): got \"%s\", R \"%s\"", REF_RPVAL[i].p, buf,
                  REF_RPVAL[i].text);
    }
}

/* Our block without its decision line is R's print.htest output. */
static void test_blocks(void)
{
    for (size_t i = 0; i < REF_NRBLOCKS; i++) {
        const ref_rblock *b = &REF_RBLOCKS[i];
        mcstat_result r;
        int st;
        if (!strcmp(b->test, "T_1"))
            st = mcstat_t_test_1(b->x, (size_t)b->nx, b->null_value, b->alternative, b->alpha, &r);
        else if (!strcmp(b->test, "T_2"))
            st = mcstat_t_test_2(b->x, (size_t)b->nx, b->y, (size_t)b->ny, b->null_value, b->alternative, b->alpha, &r);
        else
            st = mcstat_var_test_2(b->x, (size_t)b->nx, b->y, (size_t)b->ny, b->null_value, b->alternative, b->alpha,
                                   &r);
        CHECK_INT(st, MCSTAT_OK);
        char text[4096];
        size_t len;
        CHECK_INT(mcstat_result_format(&r, NULL, NULL, text, sizeof text, &len), MCSTAT_OK);
        CHECK_INT(len, strlen(text));
        char *dl = strstr(text, "decision at alpha = ");
        CHECK(dl != NULL);
        if (!dl)
            continue;
        const char *want = r.decision == 0 ? "equal" : r.decision < 0 ? "less" : "greater";
        char *eol = strchr(dl, '\n');
        CHECK(eol && (size_t)(eol - dl) > strlen(want) && !strncmp(eol - strlen(want), want, strlen(want)));
        memmove(dl, eol + 1, strlen(eol + 1) + 1);
        CHECK_MSG(!strcmp(text, b->text), "block %zu (%s):\n--- mcstat\n%s--- R\n%s---", i, b->test, text, b->text);
    }
}

static void test_buffer_sizes(void)
{
    const ref_rblock *b = &REF_RBLOCKS[0];
    mcstat_result r;
    mcstat_t_test_1(b->x, (size_t)b->nx, b->null_value, b->alternative, b->alpha, &r);
    char full[4096], small[40];
    size_t len = 0, len2 = 0;
    CHECK_INT(mcstat_result_format(&r, "x", NULL, full, sizeof full, &len), MCSTAT_OK);
    CHECK_INT(mcstat_result_format(&r, "x", NULL, small, sizeof small, &len2), MCSTAT_EBUFSIZE);
    CHECK_INT(len2, len);
    CHECK_INT(strlen(small), sizeof small - 1);
    CHECK(!strncmp(small, full, sizeof small - 1));
    /* a buffer of exactly len + 1 bytes is enough; len bytes are not */
    char *exact = malloc(len + 1);
    CHECK_INT(mcstat_result_format(&r, "x", NULL, exact, len + 1, NULL), MCSTAT_OK);
    CHECK(!strcmp(exact, full));
    CHECK_INT(mcstat_result_format(&r, "x", NULL, exact, len, NULL), MCSTAT_EBUFSIZE);
    free(exact);
    /* measuring only */
    CHECK_INT(mcstat_result_format(&r, "x", NULL, NULL, 0, &len2), MCSTAT_EBUFSIZE);
    CHECK_INT(len2, len);
    /* data names appear in the data line */
    mcstat_result_format(&r, "irradiance_S", NULL, full, sizeof full, NULL);
    CHECK(strstr(full, "data:  irradiance_S\n") != NULL);
}

int main(void)
{
    test_numbers();
    test_blocks();
    test_buffer_sizes();
    return h_report("test_format");
}
