/* good_empty.h - a user configuration that overrides nothing: config.h's defaults alone
 * must compile without a diagnostic under -Wundef -Werror (every option is defined
 * before check_config.h tests it). */
