#include <drape/drape.h>
#include <stdio.h>

int main(void) {
    drape_body body = NULL;
    if (drape_body_create(NULL, &body) != DRAPE_OK) {
        fprintf(stderr, "%s\n", drape_last_error_message());
        return 1;
    }
    printf("drape %s\n", drape_version());
    drape_body_destroy(body);
    return 0;
}
